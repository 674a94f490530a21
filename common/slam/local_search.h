#ifndef EVOSLAM_COMMON_SLAM_LOCAL_SEARCH_H_
#define EVOSLAM_COMMON_SLAM_LOCAL_SEARCH_H_

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
#include "common/slam/scan_refinement.h"
#include "common/slam/step_correction_problem.h"
#include "common/util/random.h"

namespace evoslam {

// The most particles and iterations a step's swarm may have: beyond them its memory, not its
// search, grows. The command line's flags take the same bounds.
inline constexpr std::size_t kMaxLocalParticles = 100000;
inline constexpr std::size_t kMaxLocalIterations = 100000;

// Paper 002's local search (§3.1): at every step, PSO over the odometry error of the last step.
struct LocalSearchParams {
  LocalFitness fitness = LocalFitness::kEval1;
  // The cube the error is searched in: +-x, +-y (m), +-theta (rad) per step. 002 gives no size;
  // these cover a wheeled robot's error over one step of a few tens of centimetres.
  Eigen::Vector3d max_error{0.1, 0.1, 0.05};
  // A wheeled robot's heading error grows with how far it turns: the cube's heading half-width
  // grows by this fraction of the turn odometry reports for the step. Without it, fast turns
  // (0.3 rad between two ACES scans) end on the cube's face and leave the map a few degrees off.
  double turn_error_per_rad = 0.6;
  // When odometry and laser are not read at the same instant, a fast turn's odometry splits the
  // turn unevenly between two scans: a step whose heading needed a large correction tends to be
  // followed by one that needs the opposite, beyond a cube sized by the turn odometry reports.
  // The heading's half-width also grows by this fraction of the previous step's heading
  // correction (docs/rss_slam.md).
  double carried_turn_error = 0.5;
  // ...and its centre moves from odometry's heading by minus this fraction of that correction:
  // as much of a turn as one step's odometry reported too much, the next tends to report too
  // little, and the other way round. 0: centred on odometry. With the default 6 cm cells 0.5
  // keeps ACES's fast in-place turns from slipping (docs/accuracy-history.md); with 5 cm cells it
  // does worse.
  double carried_turn_shift = 0.5;
  // That shift is a guess, and where odometry's turn runs ahead of the robot's for several scans
  // it moves the range away from the robot's turn. When it moves the centre by more than this
  // (rad), a second swarm, from its own random stream, searches the same range centred on
  // odometry's heading, and the step keeps its pose where eq. 1 counts clearly fewer cells for it
  // (by more than 2 % of the scan's beams). Our addition; 0: never (docs/rss_slam.md).
  double hedged_shift = 0.01;
  std::size_t particles = 10;  // 002
  std::size_t iterations = 30;
  double inertia = 0.7;
  double c1 = 2.0, c2 = 2.0;  // 002
  // Map cell, m. 6 cm did better than 5 on both real logs with the shift above (Intel and ACES
  // over 30 and 64 seeds); the simulated drives come out a few millimetres worse.
  double resolution = 0.06;
  // When the best correction lies on the cube's face, the step's error may lie beyond it: the
  // search runs again on a cube centred there, at most this many times, and a rerun is kept only
  // when it fits better.
  std::size_t recentres = 2;
  // When not negative, a step is scored without the returns that lie farther than the previous
  // scan's range minus this margin (m) from the previous pose. Those land beyond the map's edge
  // whatever the correction, and the shorter the step the fewer new cells they occupy, so they
  // pull every step short where the laser sees less than the place holds. The default leaves a
  // step of the simulated drives (13 cm), a cell and the range noise room; negative: every
  // return is scored, as in 002.
  double frontier_margin = 0.3;
  // Eq. 1 is flat wherever the scan pins nothing: within a cell, and along a corridor whose ends
  // the laser does not reach. There the swarm's pick among equal scores is a random point of the
  // cube, and a run of such steps drifts. Each candidate's score grows by this fraction of one
  // cell times its mean squared correction relative to the cube, so that among corrections that
  // fit alike the one nearest odometry (on a recentred cube, its centre) wins; below 1, a fit
  // one cell better always wins, and eq. 1's counts rank alike for every value in (0, 1).
  // 0: none, as in 002 (docs/rss_slam.md).
  double odometry_pull = 0.5;
  // Down a featureless corridor longer than the laser's reach nothing in the scan fixes the step
  // along the corridor, and however the ties are broken the pick drifts: the finished step keeps
  // the prediction's value along every direction whose information is below this share of the
  // best-constrained direction's (KeepPriorWhereUnconstrained). Our addition; 0: none, as in 002
  // (docs/rss_slam.md).
  double min_constraint_ratio = 0.005;
  // Where odometry errs less from one step to the next than the scan's fit (a good odometer, a
  // noisy or short-range laser), the finished step is moved toward the prediction: along a
  // direction whose information is the share m of the best-constrained direction's, it keeps
  // m / (m + odometry_weight) of the correction (KeepPriorWhereUnconstrained). Our addition; 0:
  // none. On real logs, whose odometry is poor, it costs accuracy (docs/rss_slam.md).
  double odometry_weight = 0.0;
  // Eq. 1 counts a return that lands where the map has no hit as a new cell, whether the rays so
  // far showed that cell empty or never reached it. At the edge of what has been seen (a wall a
  // corner hid, a wall just past the laser's reach, the gaps grazing beams leave along a wall)
  // every such return pulls the step back onto the part already mapped. With this on, the map
  // records the cells its rays crossed, and a return on the edge (HitCountGrid::Frontier) adds
  // no cell. Our addition; off: as in 002 (docs/rss_slam.md).
  bool free_frontier = false;
  // After the PSO, the step's pose is aligned to the map below a cell (our addition; 002 has
  // none). iterations = 0 leaves the PSO's pose, as in 002.
  ScanRefinementParams refine;
  // The map covers the odometry's path plus the laser's range plus this margin, so that drift
  // the search corrects stays on it.
  double margin = 10.0;
};

void ValidateLocalSearchParams(const LocalSearchParams& params);

// The cube the local search corrects a step in, given the step odometry reports and the heading
// correction the previous step took (rad).
Eigen::Vector3d StepErrorCube(const LocalSearchParams& params, const Pose2& odometry_step,
                              double previous_turn_correction);

// Throws Error, naming the log and the scan, when odometry moves the robot farther between two
// scans than twice the laser's reach: the two can see no point in common, so no scan matching
// can place the second, and the mark is that of a corrupt reading or a reset odometry.
void CheckOdometrySteps(const Dataset& dataset);

// The map a log's scans can reach: the odometry's path widened by the laser's range and
// params.margin. Throws Error, naming the log and its extent, when that is more than a
// HitCountGrid holds.
HitCountGrid EmptyMapFor(const Dataset& dataset, const LocalSearchParams& params);

// One step of the local search: the pose of `scan` corrected from `predicted` against `map`
// (which it leaves unchanged), and the evaluations it took.
struct StepCorrection {
  Pose2 pose;
  std::size_t evaluations = 0;
};
StepCorrection CorrectStep(const HitCountGrid& map, const LaserScan& scan, const Pose2& predicted,
                           const LocalSearchParams& params, Rng rng);

// `scan` as the local search scores it at `predicted` with params.frontier_margin = `margin`:
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
// params.max_error (FindOdometryStalls), the steps start from the stall filled in.
LocalSearchResult RunLocalSearch(
    const Dataset& dataset, const LocalSearchParams& params, std::uint64_t seed, HitCountGrid& map,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_LOCAL_SEARCH_H_
