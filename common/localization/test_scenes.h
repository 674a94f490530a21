#ifndef EVOSLAM_COMMON_LOCALIZATION_TEST_SCENES_H_
#define EVOSLAM_COMMON_LOCALIZATION_TEST_SCENES_H_

#include "common/line_map/line_map.h"
#include "common/sensor/dataset.h"
#include "common/sensor/laser_scan.h"

namespace evoslam::testing {

// A 6 x 8 m room with a few boxes: asymmetric, so a scan fixes the pose.
LineMap BoxRoom();

// The noiseless scan of `map` from `pose`: `beams` beams over 180 degrees, both ends included.
LaserScan ScanFrom(const LineMap& map, const Pose2& pose, int beams = 361, double max_range = 8.0);

// A walk of `scans` noiseless scans through BoxRoom with ground truth, and odometry that
// overestimates every step by 10 %.
Dataset WalkThroughBoxRoom(int scans);

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_LOCALIZATION_TEST_SCENES_H_
