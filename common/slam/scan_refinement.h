#ifndef EVOSLAM_COMMON_SLAM_SCAN_REFINEMENT_H_
#define EVOSLAM_COMMON_SLAM_SCAN_REFINEMENT_H_

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>

#include "common/grid/hit_count_grid.h"
#include "common/transform/pose2.h"

namespace evoslam {

// Gauss-Newton alignment of a scan to the map's occupied cells, bilinearly interpolated between
// cell centres (as Hector SLAM aligns scans). Eq. 1 is flat within a cell, so the PSO places a
// step to a cell at best; the interpolated occupancy has a slope inside the cells next to a wall,
// which the refinement follows. Returns that fall where the map has nothing pull nowhere.
struct ScanRefinementParams {
  std::size_t iterations = 10;  // 0: no refinement
  // How far the refined pose may move from the start, in map cells: the refinement chooses a
  // place within the cell the PSO found, it does not search. Along a corridor, where the scan
  // pins nothing down, a looser bound let the pose slide (docs/rss_slam.md).
  double max_shift_cells = 0.5;
  double max_turn = 0.02;  // rad
};

void ValidateScanRefinementParams(const ScanRefinementParams& params);

// The map's occupancy at a world point, interpolated between the four nearest cell centres (1 on
// occupied cells, 0 elsewhere), and its gradient per metre; nullopt where the four cells are not
// all in the grid.
struct OccupancySample {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
};
std::optional<OccupancySample> SampleOccupancy(const HitCountGrid& map,
                                               const Eigen::Vector2d& point);

// `start` moved to minimise the sum over `returns` (in the laser's frame) of (1 - occupancy)^2,
// within params.max_shift_cells and params.max_turn of it. Stops when a step does not lower the
// sum. A direction the returns do not constrain at all keeps the start's value.
Pose2 RefineScanPose(const HitCountGrid& map, std::span<const Eigen::Vector2d> returns,
                     const Pose2& start, const ScanRefinementParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_SCAN_REFINEMENT_H_
