#ifndef EVOSLAM_COMMON_SLAM_RSS_LOCAL_SEARCH_H_
#define EVOSLAM_COMMON_SLAM_RSS_LOCAL_SEARCH_H_

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/grid/hit_count_grid.h"
#include "common/io/trajectory_io.h"
#include "common/optim/particle_swarm.h"
#include "common/sensor/dataset.h"
#include "common/slam/rss/scan_refinement.h"
#include "common/slam/rss/step_correction_problem.h"
#include "common/util/random.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// The most particles and iterations a step's swarm may have: beyond them its memory, not its
// search, grows. The command line's flags take the same bounds.
inline constexpr std::size_t kMaxLocalParticles = 100000;
inline constexpr std::size_t kMaxLocalIterations = 100000;

// Paper 002's local search (§3.1): at every step, a PSO over the odometry error of the last step,
// in a cube that widens with the step's turn, then refined below a cell. What each parameter
// does, and why, is in proto/evoslam/slam_params.proto and docs/methods/rss.md.
using LocalSearchParams = proto::RssLocalSearch;

// The cube a step's error is searched in before it widens with the turn: +-x, +-y (m),
// +-theta (rad).
Eigen::Vector3d BaseErrorCube(const LocalSearchParams& params);

void ValidateLocalSearchParams(const LocalSearchParams& params);

// The cube the local search corrects a step in, given the step odometry reports and the heading
// correction the previous step took (rad).
Eigen::Vector3d StepErrorCube(const LocalSearchParams& params, const Pose2& odometry_step,
                              double previous_turn_correction);

// Throws Error, naming the log and the scan, when odometry moves the robot farther between two
// scans than twice the laser's reach: the two can see no point in common, so no scan matching
// can place the second, and the mark is that of a corrupt reading or a reset odometry.
void CheckOdometrySteps(const Dataset& dataset);

void ValidateMapParams(const proto::RssMap& params);

// The area a log's scans can reach: the odometry's path widened by the laser's range and
// map.margin_m, in cells of map.cell_size_m (counted in doubles, as there may be too many for a
// grid). Throws Error for a log without scans or bad map parameters.
struct SearchMapExtent {
  Eigen::Vector2d origin;  // the lower left corner, m
  Eigen::Vector2d size;    // m
  Eigen::Vector2d cells;   // along x and y
};
SearchMapExtent SearchMapExtentFor(const Dataset& dataset, const proto::RssMap& map);

// The map of that extent; it records the cells its rays cross when the local search frees the
// seen space's edge. Throws Error, naming the log and its extent, when that is more than a
// HitCountGrid holds.
HitCountGrid EmptyMapFor(const Dataset& dataset, const proto::RssMap& map,
                         const LocalSearchParams& local);

// One step of the local search: the pose of `scan` corrected from `predicted` within `cube`
// against `map` (which it leaves unchanged), and the evaluations it took.
struct StepCorrection {
  Pose2 pose;
  std::size_t evaluations = 0;
};
StepCorrection CorrectStep(const HitCountGrid& map, const LaserScan& scan, const Pose2& predicted,
                           const Eigen::Vector3d& cube, const LocalSearchParams& params, Rng rng);

// `scan` as the local search scores it at `predicted` with params.reach_margin_m = `margin`:
// the returns farther than previous.range_max - margin from `previous_pose` (where the previous
// scan stood) read as no return; with a negative margin, `scan` unchanged.
LaserScan WithinPreviousReach(const LaserScan& scan, const Pose2& predicted,
                              const LaserScan& previous, const Pose2& previous_pose, double margin);

// The local search's step for scan i = poses.size() > 0 of a log, `poses` holding the poses of
// scans [0, i): its pose corrected from scan i - 1's moved by the odometry's step, in the cube
// that step and the heading correction of the step before it give.
StepCorrection CorrectLogStep(const HitCountGrid& map, const Dataset& dataset,
                              std::span<const Pose2> poses, const LocalSearchParams& params,
                              Rng rng);

struct LocalSearchResult {
  std::vector<StampedPose> trajectory;  // one pose per scan, the laser's
  std::size_t evaluations = 0;
};

// Runs the local search over a whole log, inserting each scan into `map` at its corrected pose.
// The first scan keeps its odometry pose. Scan i's search draws from random stream i of the
// seed. `progress(done, total)` after every scan. Where the odometry stalls with a catch-up beyond
// the base error cube (FindOdometryStalls), the steps start from the stall filled in.
LocalSearchResult RunLocalSearch(
    const Dataset& dataset, const LocalSearchParams& params, std::uint64_t seed, HitCountGrid& map,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_RSS_LOCAL_SEARCH_H_
