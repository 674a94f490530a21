#ifndef EVOSLAM_COMMON_SENSOR_DATASET_H_
#define EVOSLAM_COMMON_SENSOR_DATASET_H_

#include <map>
#include <string>
#include <vector>

#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"

namespace evoslam {

struct OdometryReading {
  double timestamp = 0.0;
  std::string hostname = "nohost";
  double logger_timestamp = 0.0;
  Pose2 pose;
  double tv = 0.0;  // translational velocity, m/s
  double rv = 0.0;  // rotational velocity, rad/s
  double accel = 0.0;
};

// A robot log: the main (front) laser's scans in log order, the rear laser's, odometry, and the
// log's parameters. Scans carry their own odometry and, in simulated logs, ground truth.
struct Dataset {
  std::string source;  // where it was read from, for messages
  std::vector<LaserScan> scans;
  std::vector<LaserScan> rear_scans;
  std::vector<OdometryReading> odometry;
  std::vector<std::pair<std::string, std::string>> params;  // PARAM name value, in log order
  std::size_t skipped_lines = 0;  // malformed lines a lenient read skipped

  // True when every scan has a true pose.
  bool has_ground_truth() const;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SENSOR_DATASET_H_
