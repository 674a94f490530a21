#include "coordinator/progress_throttle.h"

namespace evoslam {

bool ProgressThrottle::Admit(const proto::JobStatus& report, Clock::time_point now) {
  // A new phase waits a tenth of the interval: any phase that goes on reporting for longer shows,
  // and a job that changes phase every few milliseconds still writes at most ten times an
  // interval.
  const Clock::duration wait = report.phase() != phase_ ? interval_ / 10 : interval_;
  const bool keep = !any_ || now - last_ >= wait || report.done() == report.total();
  if (!keep) return false;
  any_ = true;
  phase_ = report.phase();
  last_ = now;
  return true;
}

}  // namespace evoslam
