#ifndef EVOSLAM_COMMON_SENSOR_ODOMETRY_STALLS_H_
#define EVOSLAM_COMMON_SENSOR_ODOMETRY_STALLS_H_

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "common/sensor/dataset.h"
#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"

namespace evoslam {

// Scans [first, last] of a log repeat the odometry position of scan first - 1, and scan last + 1's
// odometry moves on from it by `catch_up` (in the frame of the repeated reading). A raw log
// repeats a reading when the odometry messages were held up while the laser went on, and the
// next fresh reading then carries all the motion since, sometimes tens of centimetres and tens
// of degrees at once. Some logs hold only the position while the heading reads on.
struct OdometryStall {
  std::size_t first = 0;
  std::size_t last = 0;
  Pose2 catch_up;
  // Whether the heading repeated too; when it did not, the readings' headings are live.
  bool heading_held = true;
};

// Every run of scans that repeat the whole odometry reading before them and is ended by a scan
// whose reading moves on, with that scan's catch-up: a robot standing still, or a stall.
std::vector<OdometryStall> FindRepeatedReadings(std::span<const LaserScan> scans);

// The stalls of `scans` that a search of a small cube, `absorbed` (x, y, heading), around each
// odometry step cannot follow: a run of repeated positions whose catch-up exceeds the cube along
// x or y, or else a run of repeated readings within it whose catch-up exceeds it along any of the
// three. A robot standing still repeats its reading, and one turning on the spot its position, but
// the step that ends such a run is small.
std::vector<OdometryStall> FindOdometryStalls(std::span<const LaserScan> scans,
                                              const Eigen::Vector3d& absorbed);

// Each stall's odometry spread between the readings either side of it (scans first - 1 and
// last + 1) in proportion to the scans' timestamps, or to their indices where the timestamps do
// not increase: the motion the late reading reports, as it happened while the laser scanned. Of a
// stall whose heading read on, only the positions are spread and the headings are kept.
// `stalls` must come from FindOdometryStalls on these scans.
void FillOdometryStalls(std::span<LaserScan> scans, std::span<const OdometryStall> stalls);

// `run(dataset)`, or `run` over a copy of `dataset` with `stalls` filled when there are any: only
// a log that stalled pays for the copy.
template <typename Run>
auto RunWithOdometryStallsFilled(const Dataset& dataset, std::span<const OdometryStall> stalls,
                                 Run&& run) {
  if (stalls.empty()) return std::forward<Run>(run)(dataset);
  Dataset filled = dataset;
  FillOdometryStalls(filled.scans, stalls);
  return std::forward<Run>(run)(std::as_const(filled));
}

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SENSOR_ODOMETRY_STALLS_H_
