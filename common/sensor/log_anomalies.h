#ifndef EVOSLAM_COMMON_SENSOR_LOG_ANOMALIES_H_
#define EVOSLAM_COMMON_SENSOR_LOG_ANOMALIES_H_

#include <cstddef>
#include <span>
#include <vector>

#include "common/sensor/laser_scan.h"

namespace evoslam {

// The odometry moves `length_m` from scan `from` to scan `from + 1`.
struct OdometryJump {
  std::size_t from = 0;
  double length_m = 0.0;
};

// Scan `scan`'s timestamp lies `back_s` seconds before the previous scan's. The scans are used in
// file order regardless: a clock that jumps back is the clock's fault, not the scans' order.
struct TimeReversal {
  std::size_t scan = 0;
  double back_s = 0.0;
};

// What in a log's scans deserves a warning before it is mapped: odometry steps far longer than the
// log's pace (a reset or corrupt reading draws a straight line across the map) and timestamps that
// go back. Found on the scans as read, before stalls are filled, so that each names the scans
// where it happened.
struct LogAnomalies {
  // The log's pace: the median length of the odometry steps that move; 0 with fewer than
  // kMinStepsForPace of them, too few to tell a pace from a jump.
  double typical_step_m = 0.0;
  std::vector<OdometryJump> jumps;
  std::vector<TimeReversal> reversals;
};

// A step is a jump when it is longer than kJumpOverTypicalStep typical steps and kMinJump metres.
inline constexpr double kJumpOverTypicalStep = 20.0;
inline constexpr double kMinJump = 1.0;
inline constexpr std::size_t kMinStepsForPace = 10;

LogAnomalies FindLogAnomalies(std::span<const LaserScan> scans);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SENSOR_LOG_ANOMALIES_H_
