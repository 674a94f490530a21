#ifndef EVOSLAM_COMMON_SENSOR_DATASET_SUMMARY_H_
#define EVOSLAM_COMMON_SENSOR_DATASET_SUMMARY_H_

#include <cstddef>
#include <string>

#include "common/sensor/dataset.h"
#include "common/sensor/log_anomalies.h"

namespace evoslam {

// What a log holds, for `evoslam info` and for checking that a log was read as expected.
// Beam and geometry figures describe the main (front) laser's scans; all zero without scans.
struct DatasetSummary {
  std::size_t scans = 0;
  std::size_t rear_scans = 0;
  std::size_t odometry_readings = 0;
  std::size_t min_beams = 0;
  std::size_t max_beams = 0;
  double field_of_view_deg = 0.0;     // largest over the scans, first to last beam
  double angle_increment_deg = 0.0;   // of the first scan
  double max_range = 0.0;             // largest range_max over the scans (the sensor's limit)
  double start_time = 0.0;            // earliest timestamp of any message
  double end_time = 0.0;              // latest timestamp of any message
  double duration = 0.0;              // end_time - start_time
  double odometry_path_length = 0.0;  // metres travelled according to odometry
  // Runs of scans whose odometry repeats the reading before them, ended by a scan whose reading
  // moves on: a robot standing still, or odometry held up while the laser went on (then the
  // step that ends the run is large; OdometryStall). Of the steps that end them, the longest and
  // the largest turn.
  std::size_t odometry_repeats = 0;
  std::size_t longest_odometry_repeat = 0;  // scans
  double largest_catch_up_m = 0.0;
  double largest_catch_up_deg = 0.0;
  bool has_ground_truth = false;
  LogAnomalies anomalies;  // of the front scans
};

DatasetSummary Summarize(const Dataset& dataset);

// A readable multi-line description, each line ending in '\n'.
std::string FormatSummary(const DatasetSummary& summary);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SENSOR_DATASET_SUMMARY_H_
