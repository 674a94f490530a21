#include "common/service/job_progress.h"

#include <utility>

#include "common/service/job_state.h"

namespace evoslam {

std::string StepText(const proto::JobStatus& status) {
  if (!status.has_step() || status.step().name().empty()) return "";
  std::string text = status.step().name();
  if (status.step().total() > 0) {
    text +=
        " " + std::to_string(status.step().done()) + "/" + std::to_string(status.step().total());
  }
  return text;
}

JobProgress::JobProgress(ProgressBar::Output output) : output_(std::move(output)) {}

void JobProgress::Show(const proto::JobStatus& status) {
  if (!bar_) {
    if (status.total() == 0) return;
    bar_.emplace(std::string(JobKindName(status.kind())), "scans", status.total(), output_);
  }
  bar_->Update(status.done(), StepText(status));
}

}  // namespace evoslam
