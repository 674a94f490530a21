#ifndef EVOSLAM_COMMON_SLAM_PLACE_MATCHER_H_
#define EVOSLAM_COMMON_SLAM_PLACE_MATCHER_H_

#include <Eigen/Core>
#include <span>
#include <vector>

#include "common/grid/grid_geometry.h"
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

  // The share of `points` (laser frame) seen from `pose` that land near the place's obstacles
  // (the field at least kNearField) and see them from the side the place saw them: their beam
  // meets the surface at the nearest return from the side its normal faces (the normal across
  // that return's neighbours in its scan, turned toward its laser). Beams along a corridor from
  // its two ends see its walls from one side; from inside a block, from the other. A pose behind
  // the walls it matches (inside a block whose faces the place saw from outside, or in the next
  // room through a wall) lines the returns up with them as well as the right pose does, but sees
  // each wall from its far side. 1 when no point lands near an obstacle.
  double SideAgreement(std::span<const Eigen::Vector2d> points, const Pose2& pose) const;

  // Score at every translation of a (2 half_steps + 1)^2 lattice of `step` metres around
  // `center`, at heading `theta`, into `scores` row by row from the lowest y. A step of one cell
  // or of two (the coarse lattice's) takes a shortcut: each point's cell is found once, not once a
  // translation.
  void ScoreTranslations(std::span<const Eigen::Vector2d> points, const Pose2& center, double theta,
                         double step, int half_steps, std::vector<double>& scores) const;

  struct Match {
    Pose2 pose;
    double score = 0.0;
    // How far the best pose stands out: the coarse lattice's best score less its best score at
    // least `rival_distance` metres away. Near 0, the place matches about as well elsewhere (a
    // corridor along its length, two rooms alike), and the pose found cannot be trusted.
    double distinctness = 0.0;
  };
  // The best pose within +-window (m) and +-window_theta (rad) of `center`: a coarse lattice on
  // every other point, then two finer lattices around the best on all points. Ties go to the
  // first in lattice order, so the result is deterministic.
  Match Search(std::span<const Eigen::Vector2d> points, const Pose2& center, double window,
               double window_theta, double rival_distance) const;

 private:
  // The best pose of a lattice around `center`; with `rival_distance`, also its distinctness.
  Match Lattice(std::span<const Eigen::Vector2d> points, const Pose2& center, double step,
                int half_steps, double step_theta, int half_steps_theta, int stride,
                double rival_distance = 0.0) const;

  // The coarse lattice's step, in cells.
  static constexpr int kCoarseStepCells = 2;
  // Near an obstacle for SideAgreement: within about 1.2 sigma of a return.
  static constexpr float kNearField = 0.5f;

  GridGeometry geometry_;     // the field's cells: none when the place has no returns
  std::vector<float> field_;  // a value per cell, by its index in geometry_
  // The place's returns (world frame) scan by scan: scan k's are [scan_starts_[k],
  // scan_starts_[k + 1]), seen from lasers_[k].
  std::vector<Eigen::Vector2d> hits_;
  std::vector<std::size_t> scan_starts_;
  std::vector<Eigen::Vector2d> lasers_;
  // The field again, its columns grouped by their remainder modulo kCoarseStepCells (all rows of
  // remainder 0, then of 1, ...): along a row of the coarse lattice a point's cells lie side by
  // side here, which the vectoriser loads whole where the field would need a gather.
  std::vector<float> coarse_field_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_PLACE_MATCHER_H_
