#include "common/sensor/log_anomalies.h"

#include <algorithm>
#include <cmath>

namespace evoslam {

LogAnomalies FindLogAnomalies(std::span<const LaserScan> scans) {
  LogAnomalies found;
  std::vector<double> moving;
  for (std::size_t i = 1; i < scans.size(); ++i) {
    const double step =
        (scans[i].odometry.translation() - scans[i - 1].odometry.translation()).norm();
    if (step > 0.0) moving.push_back(step);
    if (scans[i].timestamp < scans[i - 1].timestamp) {
      found.reversals.push_back({i, scans[i - 1].timestamp - scans[i].timestamp});
    }
  }
  if (moving.size() >= kMinStepsForPace) {
    const auto median = moving.begin() + static_cast<std::ptrdiff_t>(moving.size() / 2);
    std::nth_element(moving.begin(), median, moving.end());
    found.typical_step_m = *median;
  }
  const double threshold = std::max(kMinJump, kJumpOverTypicalStep * found.typical_step_m);
  for (std::size_t i = 1; i < scans.size(); ++i) {
    const double step =
        (scans[i].odometry.translation() - scans[i - 1].odometry.translation()).norm();
    // Also a step that is not a number: a corrupt reading.
    if (!(step <= threshold)) found.jumps.push_back({i - 1, step});
  }
  return found;
}

}  // namespace evoslam
