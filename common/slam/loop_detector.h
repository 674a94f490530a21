#ifndef EVOSLAM_COMMON_SLAM_LOOP_DETECTOR_H_
#define EVOSLAM_COMMON_SLAM_LOOP_DETECTOR_H_

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>

#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// A place seen twice: scan `later` should sit at `relative` in scan `earlier`'s frame.
struct LoopConstraint {
  std::size_t earlier = 0;
  std::size_t later = 0;
  Pose2 relative;
};

// When the robot is back in a place it has mapped and its scan does not fit the map there: the
// rule that starts a loop-closing global search. A revisit lies near an earlier pose, far enough
// back in scans and path; the scan is matched against that place's map in a window that widens
// with the path between the visits, as drift does; the match must score well, stand out from its
// rivals, see the place's walls from the side the place saw them, and move the scan further than
// the match's own error (proto/evoslam/slam_params.proto, docs/methods/rss.md).
using LoopDetectionParams = proto::LoopDetection;

void ValidateLoopDetectionParams(const LoopDetectionParams& params);

// The match window's half-width (m) for a revisit `travelled` metres of path after the earlier
// visit; the revisit radius is revisit_radius plus what this adds to match_window.
double MatchWindow(const LoopDetectionParams& params, double travelled);

// Whether a scan that its match moves by `shift` (in the scan's frame) already fits where the
// trajectory puts it: within fit_tolerance_m and fit_tolerance_rad. Measured as eq. 7 measures the
// loop's miss, a loop that a search closed is not found again at the next check.
bool FitsWhereItIs(const Pose2& shift, const LoopDetectionParams& params);

// A place seen twice, found by matching.
struct LoopClosure {
  LoopConstraint constraint;
  double score = 0.0;         // the match's likelihood score, 0 to 1
  double distinctness = 0.0;  // how far the match stands out (PlaceMatcher::Match)
};

// Checks scan `current` (its pose poses[current]) against the places the trajectory passed
// before; poses holds the poses of scans [0, current]. Returns the loop when the scan is a
// revisit of an earlier place whose match is trusted and does not fit the trajectory.
std::optional<LoopClosure> DetectLoop(std::span<const LaserScan> scans,
                                      std::span<const Pose2> poses, std::size_t current,
                                      const LoopDetectionParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_LOOP_DETECTOR_H_
