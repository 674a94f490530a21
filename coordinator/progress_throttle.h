#ifndef EVOSLAM_COORDINATOR_PROGRESS_THROTTLE_H_
#define EVOSLAM_COORDINATOR_PROGRESS_THROTTLE_H_

#include <chrono>
#include <string>

#include "evoslam/service.pb.h"

namespace evoslam {

// Which of a job's progress reports the coordinator records. A record costs a database write and
// an event to every watcher, and a job reports every scan, so while the phase and the step under
// way stay the same at most one report per interval is kept, plus the one that completes the job.
// A report whose phase or step (by name, or none) differs from the last one recorded is kept after
// a tenth of the interval: a stretch of scans between two global searches can be shorter than the
// interval, and a watcher (or a test waiting for the job to be part-way) would otherwise never see
// it.
class ProgressThrottle {
 public:
  using Clock = std::chrono::steady_clock;

  explicit ProgressThrottle(Clock::duration interval) : interval_(interval) {}

  // Whether to record `report`, made at `now`; when so, it counts as the last one recorded.
  bool Admit(const proto::JobStatus& report, Clock::time_point now);

 private:
  Clock::duration interval_;
  bool any_ = false;
  std::string phase_;
  bool step_ = false;
  std::string step_name_;
  Clock::time_point last_{};
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_PROGRESS_THROTTLE_H_
