#ifndef EVOSLAM_COMMON_SLAM_RSS_SCAN_REFINEMENT_H_
#define EVOSLAM_COMMON_SLAM_RSS_SCAN_REFINEMENT_H_

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>

#include "common/grid/hit_count_grid.h"
#include "common/transform/pose2.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// Gauss-Newton alignment of a scan to the map's occupancy, bilinearly interpolated between cell
// centres (as Hector SLAM aligns scans). Eq. 1 is flat within a cell, so the PSO places a step to
// a cell at best; the interpolated occupancy has a slope inside the cells next to a wall, which
// the refinement follows. Returns that fall where the map has nothing pull nowhere. Its bound
// keeps it within the cell the PSO found: it chooses a place there, it does not search. A cell's
// occupancy is its count against wall_share of the strongest count in the 4 by 4 cells around the
// point, at most 1: range noise scatters a wall's hits into the cells either side of it, so read
// this way the occupancy peaks along the wall, and a wall's cells, whose counts vary along it,
// stay level with one another and do not push a pose along a corridor (docs/methods/rss.md).
using ScanRefinementParams = proto::ScanRefinement;

void ValidateScanRefinementParams(const ScanRefinementParams& params);

// The map's occupancy at a world point, interpolated between the four nearest cell centres (each
// read as ScanRefinementParams::wall_share says), and its gradient per metre; nullopt where the
// four cells are not all in the grid.
struct OccupancySample {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
};
std::optional<OccupancySample> SampleOccupancy(const HitCountGrid& map,
                                               const Eigen::Vector2d& point, double wall_share);

// The normal matrix J^T J of the refinement's least squares at `pose`, in (x, y, heading): how
// strongly the returns pin each direction down.
Eigen::Matrix3d ScanInformation(const HitCountGrid& map, std::span<const Eigen::Vector2d> returns,
                                const Pose2& pose, double wall_share);

struct RefinedPose {
  Pose2 pose;
  // ScanInformation at `pose`, which the refinement has already summed; the constraint rule
  // reads it there rather than summing it again.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

// `start` moved to minimise the sum over `returns` (in the laser's frame) of (1 - occupancy)^2,
// within params.max_shift_cells and params.max_turn of it. Stops when a step does not lower the
// sum. A direction the returns do not constrain at all keeps the start's value.
RefinedPose RefineScanPose(const HitCountGrid& map, std::span<const Eigen::Vector2d> returns,
                           const Pose2& start, const ScanRefinementParams& params);

// `pose` with its offset from `prior` kept only along the directions the returns constrain: along
// a direction whose information (an eigenvalue of `information`, ScanInformation at `pose`, the
// heading measured by the returns' mean range) is below `min_ratio` times the best-constrained
// direction's, the prior's value is taken. Down a featureless corridor longer than the laser's
// reach the scan fixes nothing along the corridor, and a search's pick there is noise. With
// `prior_weight` w > 0, a direction whose information is the share m >= min_ratio of the best's
// keeps m / (m + w) of the offset: the prior weighs as w times the best direction's information,
// as when odometry errs less from one step to the next than the scan's fit. Returns `pose` for
// min_ratio <= 0 and w = 0, or for no returns, and `prior` where the map constrains nothing at all.
Pose2 KeepPriorWhereUnconstrained(const Eigen::Matrix3d& information,
                                  std::span<const Eigen::Vector2d> returns, const Pose2& pose,
                                  const Pose2& prior, double min_ratio, double prior_weight = 0.0);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_RSS_SCAN_REFINEMENT_H_
