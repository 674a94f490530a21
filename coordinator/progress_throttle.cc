#include "coordinator/progress_throttle.h"

namespace evoslam {

bool ProgressThrottle::Admit(const proto::JobStatus& report, Clock::time_point now) {
  // A new phase or step waits a tenth of the interval: any that goes on reporting for longer
  // shows, and a job that changes step every few milliseconds still writes at most ten times an
  // interval.
  const bool changed =
      report.phase() != phase_ || report.has_step() != step_ || report.step().name() != step_name_;
  const Clock::duration wait = changed ? interval_ / 10 : interval_;
  const bool keep = !any_ || now - last_ >= wait || report.done() == report.total();
  if (!keep) return false;
  any_ = true;
  phase_ = report.phase();
  step_ = report.has_step();
  step_name_ = report.step().name();
  last_ = now;
  return true;
}

}  // namespace evoslam
