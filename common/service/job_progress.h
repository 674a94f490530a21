#ifndef EVOSLAM_COMMON_SERVICE_JOB_PROGRESS_H_
#define EVOSLAM_COMMON_SERVICE_JOB_PROGRESS_H_

#include <optional>
#include <string>

#include "common/util/progress_bar.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// The step under way inside a job, as its progress shows it: "global search 3/10"; empty when
// there is none.
std::string StepText(const proto::JobStatus& status);

// What a client shows of a job it follows: one ProgressBar for the whole job, labelled with its
// kind ("slam"), made when the job first says how many scans it has and fed every status after,
// whatever its phase or step; the step appears inside it.
class JobProgress {
 public:
  explicit JobProgress(ProgressBar::Output output = ProgressBar::ForStderr());
  void Show(const proto::JobStatus& status);

 private:
  ProgressBar::Output output_;
  std::optional<ProgressBar> bar_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_JOB_PROGRESS_H_
