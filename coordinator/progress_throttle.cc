#include "coordinator/progress_throttle.h"

namespace evoslam {

bool ProgressThrottle::Admit(const proto::JobStatus& report, Clock::time_point now) {
  const bool keep = !any_ || report.phase() != phase_ || now - last_ >= interval_ ||
                    report.done() == report.total();
  if (!keep) return false;
  any_ = true;
  phase_ = report.phase();
  last_ = now;
  return true;
}

}  // namespace evoslam
