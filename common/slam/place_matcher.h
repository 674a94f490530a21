#ifndef EVOSLAM_COMMON_SLAM_PLACE_MATCHER_H_
#define EVOSLAM_COMMON_SLAM_PLACE_MATCHER_H_

#include <Eigen/Core>
#include <span>
#include <vector>

#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"

namespace evoslam {

// A place's obstacles as a likelihood field (each cell holds exp(-d^2 / 2 sigma^2) of its
// distance d to the nearest return, cut at 3 sigma), and an exhaustive search for the pose of a
// scan in it: the correlative matching loop detection needs, where the local search's small cube
// cannot reach.
class PlaceMatcher {
 public:
  // The place: `scans` seen at `poses`. The field covers their returns plus `margin` metres.
  PlaceMatcher(std::span<const LaserScan> scans, std::span<const Pose2> poses, double resolution,
               double sigma, double margin);

  // The mean likelihood of `points` (laser frame) seen from `pose`, 0 to 1.
  double Score(std::span<const Eigen::Vector2d> points, const Pose2& pose) const;

  struct Match {
    Pose2 pose;
    double score = 0.0;
  };
  // The best pose within +-window (m) and +-window_theta (rad) of `center`: a coarse lattice on
  // every other point, then two finer lattices around the best on all points. Ties go to the
  // first in lattice order, so the result is deterministic.
  Match Search(std::span<const Eigen::Vector2d> points, const Pose2& center, double window,
               double window_theta) const;

 private:
  Match Lattice(std::span<const Eigen::Vector2d> points, const Pose2& center, double step,
                int half_steps, double step_theta, int half_steps_theta, int stride) const;

  double resolution_;
  Eigen::Vector2d origin_;
  int width_ = 0, height_ = 0;
  std::vector<float> field_;  // row-major
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_PLACE_MATCHER_H_
