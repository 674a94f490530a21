#ifndef EVOSLAM_COMMON_SENSOR_LASER_SCAN_H_
#define EVOSLAM_COMMON_SENSOR_LASER_SCAN_H_

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/transform/pose2.h"

namespace evoslam {

// Which CARMEN message a scan came from; the writer uses it to round-trip logs.
enum class LaserMessage { kFront, kRear, kRobotLaser };

// One sweep of a 2D range finder. Beam i points at angle_min + i * angle_increment in the robot
// frame; ranges are metres. A reading is a return only when it lies in (range_min, range_max).
struct LaserScan {
  double timestamp = 0.0;  // ipc_timestamp, seconds
  std::string hostname = "nohost";
  double logger_timestamp = 0.0;
  LaserMessage message = LaserMessage::kFront;

  double angle_min = 0.0;
  double angle_increment = 0.0;
  double range_min = 0.0;
  double range_max = 0.0;
  std::vector<float> ranges;

  Pose2 pose;                      // the pose the log states for the scan (FLASER x y theta)
  Pose2 odometry;                  // raw odometry at the scan
  std::optional<Pose2> true_pose;  // ground truth, from a TRUEPOS line with the same timestamp

  std::size_t size() const { return ranges.size(); }
  double angle(std::size_t i) const { return angle_min + static_cast<double>(i) * angle_increment; }
  double field_of_view() const;  // angle from the first to the last beam
  bool is_return(std::size_t i) const;
};

// The end points of a scan's returns in the laser's own frame, in beam order.
std::vector<Eigen::Vector2d> ReturnPoints(const LaserScan& scan);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SENSOR_LASER_SCAN_H_
