#include "common/slam/rss/local_search.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "common/optim/evolve.h"
#include "common/sensor/odometry_stalls.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// The random stream of a step's second swarm, beyond those of its recentred searches.
constexpr std::uint64_t kHedgeStream = 1000;
// The second swarm's pose is kept only when eq. 1 counts fewer cells for it than for the first
// swarm's by more than this share of the scan's beams: two poses refined below a cell differ by a
// cell or two by chance (docs/methods/rss.md).
constexpr double kHedgeWinShare = 0.02;

// Whether a correction lies within 5 % of the cube's face on some axis, where the step's error
// may lie beyond the cube.
bool OnFace(const Eigen::VectorXd& error, const Eigen::Vector3d& max_error) {
  constexpr double kFace = 0.95;
  for (int axis = 0; axis < 3; ++axis) {
    if (max_error(axis) > 0.0 && std::abs(error(axis)) >= kFace * max_error(axis)) return true;
  }
  return false;
}

}  // namespace

void ValidateLocalSearchParams(const LocalSearchParams& p) {
  if (!(BaseErrorCube(p).array() >= 0.0).all() || !BaseErrorCube(p).allFinite())
    throw Error("local.max_error_*: the step's error cube must be finite and not negative");
  if (p.particles() < 2 || p.particles() > kMaxLocalParticles)
    throw Error("local.particles: from 2 to " + std::to_string(kMaxLocalParticles));
  if (p.iterations() == 0 || p.iterations() > kMaxLocalIterations)
    throw Error("local.iterations: from 1 to " + std::to_string(kMaxLocalIterations));
  ParseLocalFitness(p.fitness());
  if (!IsFiniteNonNegative(p.heading_range_per_turn()))
    throw Error("local.heading_range_per_turn: must be finite and not negative");
  if (!std::isfinite(p.heading_shift_per_correction()))
    throw Error("local.heading_shift_per_correction: must be finite");
  if (!IsFiniteNonNegative(p.second_swarm_above_rad()))
    throw Error("local.second_swarm_above_rad: must be finite and not negative");
  if (!IsFiniteNonNegative(p.heading_range_per_correction()))
    throw Error("local.heading_range_per_correction: must be finite and not negative");
  if (p.recentres() > 100) throw Error("local.recentres: at most 100");
  if (!(p.odometry_tie_pull() >= 0.0 && p.odometry_tie_pull() < 1.0))
    throw Error("local.odometry_tie_pull: must be in [0, 1)");
  if (!(p.odometry_below_information() >= 0.0 && p.odometry_below_information() < 1.0))
    throw Error("local.odometry_below_information: must be in [0, 1)");
  if (!IsFiniteNonNegative(p.odometry_weight()))
    throw Error("local.odometry_weight: must be finite and not negative");
  if (!std::isfinite(p.reach_margin_m())) throw Error("local.reach_margin_m: must be finite");
  if (!std::isfinite(p.inertia()) || !std::isfinite(p.cognitive()) || !std::isfinite(p.social()))
    throw Error("local.inertia, local.cognitive and local.social: must be finite");
  ValidateScanRefinementParams(p.refine());
}

void ValidateMapParams(const proto::RssMap& params) {
  if (!(params.cell_size_m() > 0.0) || !std::isfinite(params.cell_size_m()))
    throw Error("map.cell_size_m: must be finite and positive");
  if (!(params.margin_m() >= 0.0) || !std::isfinite(params.margin_m()))
    throw Error("map.margin_m: must be finite and not negative");
}

Eigen::Vector3d BaseErrorCube(const LocalSearchParams& params) {
  return {params.max_error_x_m(), params.max_error_y_m(), params.max_error_theta_rad()};
}

Eigen::Vector3d StepErrorCube(const LocalSearchParams& params, const Pose2& odometry_step,
                              double previous_turn_correction) {
  Eigen::Vector3d cube = BaseErrorCube(params);
  cube.z() += params.heading_range_per_turn() * std::abs(odometry_step.theta()) +
              params.heading_range_per_correction() * std::abs(previous_turn_correction);
  return cube;
}

void CheckOdometrySteps(const Dataset& dataset) {
  for (std::size_t i = 1; i < dataset.scans.size(); ++i) {
    const LaserScan& previous = dataset.scans[i - 1];
    const LaserScan& scan = dataset.scans[i];
    const double step =
        (scan.odometry.translation() - previous.odometry.translation()).stableNorm();
    const double reach = std::max(previous.range_max, scan.range_max);
    if (step <= 2 * reach) continue;  // also refuses NaN
    std::ostringstream os;
    os << dataset.source << ": odometry moves " << step << " m from scan " << i - 1 << " to scan "
       << i << ", more than twice the laser's " << reach
       << " m reach, so the two scans see nothing in common (a corrupt or reset odometry "
          "reading?); scan "
       << i << " is at t = " << std::fixed << std::setprecision(3) << scan.timestamp << " s";
    throw Error(os.str());
  }
}

SearchMapExtent SearchMapExtentFor(const Dataset& dataset, const proto::RssMap& params) {
  ValidateMapParams(params);
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  double reach = 0.0;
  for (const LaserScan& s : dataset.scans) {
    lo = lo.cwiseMin(s.odometry.translation());
    hi = hi.cwiseMax(s.odometry.translation());
    reach = std::max(reach, s.range_max);
  }
  const double pad = reach + params.margin_m();
  SearchMapExtent extent;
  extent.origin = lo.array() - pad;
  extent.size = (hi - lo).array() + 2 * pad;
  // Counted in doubles, so that a path of 1e300 m is refused rather than overflowing the count.
  extent.cells = (extent.size / params.cell_size_m()).array().ceil() + 1.0;
  return extent;
}

HitCountGrid EmptyMapFor(const Dataset& dataset, const proto::RssMap& params,
                         const LocalSearchParams& local) {
  const SearchMapExtent extent = SearchMapExtentFor(dataset, params);
  const Eigen::Vector2d& cells = extent.cells;
  if (!(cells.x() * cells.y() <= static_cast<double>(HitCountGrid::kMaxCells))) {
    std::ostringstream os;
    os << dataset.source << ": the odometry's path and the laser's reach span " << extent.size.x()
       << " x " << extent.size.y() << " m, more than the " << HitCountGrid::kMaxCells
       << " cells of " << params.cell_size_m()
       << " m the search's map holds; map at a coarser resolution";
    throw Error(os.str());
  }
  HitCountGrid map(params.cell_size_m(), extent.origin, static_cast<int>(cells.x()),
                   static_cast<int>(cells.y()));
  if (local.free_frontier()) map.TrackRays();
  return map;
}

StepCorrection CorrectStep(const HitCountGrid& map, const LaserScan& scan, const Pose2& predicted,
                           const Eigen::Vector3d& cube, const LocalSearchParams& params, Rng rng) {
  PsoParams pso;
  pso.particles = params.particles();
  pso.inertia = params.inertia();
  pso.c1 = params.cognitive();
  pso.c2 = params.social();
  StopCriteria stop;
  stop.max_generations = params.iterations();
  const LocalFitness fitness = ParseLocalFitness(params.fitness());
  StepCorrection result{predicted, 0};
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t round = 0; round <= params.recentres(); ++round) {
    const StepCorrectionProblem problem(map, scan, result.pose, cube, fitness,
                                        params.odometry_tie_pull(), params.free_frontier());
    ParticleSwarm swarm(pso);
    Rng stream = round == 0 ? rng : rng.Stream(round);
    const OptimResult r = Minimize(problem, swarm, stop, stream);
    result.evaluations += r.evaluations;
    if (!(r.best_fitness < best)) break;  // the recentred cube found nothing better
    best = r.best_fitness;
    result.pose = problem.Corrected(r.best);
    if (!OnFace(r.best, cube)) break;
  }
  if (params.refine().iterations() == 0 && params.odometry_below_information() == 0.0 &&
      params.odometry_weight() == 0.0) {
    return result;
  }
  std::vector<Eigen::Vector2d> returns = ReturnPoints(scan);
  if (params.free_frontier()) {
    // The interpolated occupancy slopes from a mapped wall's end into the edge beyond it, so a
    // return there would pull the refinement, and read as information, as it pulled eq. 1.
    const Pose2Frame frame(result.pose);
    std::erase_if(returns, [&](const Eigen::Vector2d& p) {
      const std::optional<std::size_t> cell = map.CellIndex(frame * p);
      return cell && map.Frontier(*cell);
    });
  }
  RefinedPose refined{result.pose};
  if (params.refine().iterations() > 0) {
    refined = RefineScanPose(map, returns, result.pose, params.refine());
  } else {
    refined.information = ScanInformation(map, returns, result.pose, params.refine().wall_share());
  }
  result.pose =
      KeepPriorWhereUnconstrained(refined.information, returns, refined.pose, predicted,
                                  params.odometry_below_information(), params.odometry_weight());
  return result;
}

LaserScan WithinPreviousReach(const LaserScan& scan, const Pose2& predicted,
                              const LaserScan& previous, const Pose2& previous_pose,
                              double margin) {
  LaserScan scored = scan;
  if (margin < 0.0) return scored;
  const Pose2 relative = previous_pose.inverse() * predicted;
  const double reach = previous.range_max - margin;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan.is_return(i)) continue;
    const double r = scan.ranges[i], a = scan.angle(i);
    const Eigen::Vector2d seen_from_previous =
        relative * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
    if (seen_from_previous.norm() > reach) scored.ranges[i] = static_cast<float>(scan.range_max);
  }
  return scored;
}

StepCorrection CorrectLogStep(const HitCountGrid& map, const Dataset& dataset,
                              std::span<const Pose2> poses, const LocalSearchParams& params,
                              Rng rng) {
  const std::size_t i = poses.size();
  if (i == 0 || i >= dataset.scans.size()) {
    throw Error("local search: scan " + std::to_string(i) + " has no step to correct");
  }
  const LaserScan& scan = dataset.scans[i];
  const LaserScan& previous = dataset.scans[i - 1];
  const Pose2& previous_pose = poses[i - 1];
  const Pose2 step = previous.odometry.inverse() * scan.odometry;
  double previous_turn_correction = 0.0;
  if (i >= 2) {
    const Pose2 odometry_before = dataset.scans[i - 2].odometry.inverse() * previous.odometry;
    const Pose2 taken_before = poses[i - 2].inverse() * previous_pose;
    previous_turn_correction = (odometry_before.inverse() * taken_before).theta();
  }
  const double shift = -params.heading_shift_per_correction() * previous_turn_correction;
  const Pose2 predicted = previous_pose * step * Pose2(0.0, 0.0, shift);
  const Eigen::Vector3d cube = StepErrorCube(params, step, previous_turn_correction);
  const LaserScan scored =
      WithinPreviousReach(scan, predicted, previous, previous_pose, params.reach_margin_m());
  const StepCorrection shifted = CorrectStep(map, scored, predicted, cube, params, rng);
  const double hedge_above = params.second_swarm_above_rad();
  if (hedge_above == 0.0 || !(std::abs(shift) > hedge_above)) return shifted;
  const Pose2 unshifted = previous_pose * step;
  const StepCorrection hedge =
      CorrectStep(map, scored, unshifted, cube, params, rng.Stream(kHedgeStream));
  // By eq. 1 whatever the search's fitness, since eq. 2 ranks alike and eq. 1's counts give the
  // margin a unit. The two counts differ only by the cells each pose's returns add, wherever they
  // land, so the judge's own window and cube do not matter.
  const StepCorrectionProblem judge(map, scored, predicted, cube, LocalFitness::kEval1, 0.0,
                                    params.free_frontier());
  const auto cells = [&](const Pose2& pose) {
    const Pose2 error = predicted.inverse() * pose;
    return judge.Score(Eigen::Vector3d(error.x(), error.y(), error.theta()));
  };
  const double margin = kHedgeWinShare * static_cast<double>(scan.size());
  const bool hedge_fits_better = cells(hedge.pose) < cells(shifted.pose) - margin;
  StepCorrection kept = hedge_fits_better ? hedge : shifted;
  kept.evaluations = shifted.evaluations + hedge.evaluations;
  return kept;
}

namespace {

// RunLocalSearch over a log whose odometry stalls are filled.
LocalSearchResult RunOverFilledLog(const Dataset& dataset, const LocalSearchParams& params,
                                   std::uint64_t seed, HitCountGrid& map,
                                   const std::function<void(std::size_t, std::size_t)>& progress) {
  CheckOdometrySteps(dataset);
  const Rng root(seed);
  LocalSearchResult result;
  const std::size_t n = dataset.scans.size();
  result.trajectory.reserve(n);
  std::vector<Pose2> poses;
  poses.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const LaserScan& scan = dataset.scans[i];
    Pose2 pose = scan.odometry;
    if (i > 0) {
      const StepCorrection c = CorrectLogStep(map, dataset, poses, params, root.Stream(i));
      pose = c.pose;
      result.evaluations += c.evaluations;
    }
    poses.push_back(pose);
    map.AddScan(scan, pose);
    result.trajectory.push_back({scan.timestamp, pose});
    if (progress) progress(i + 1, n);
  }
  return result;
}

}  // namespace

LocalSearchResult RunLocalSearch(const Dataset& dataset, const LocalSearchParams& params,
                                 std::uint64_t seed, HitCountGrid& map,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  ValidateLocalSearchParams(params);
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  const std::vector<OdometryStall> stalls =
      FindOdometryStalls(dataset.scans, BaseErrorCube(params));
  return RunWithOdometryStallsFilled(dataset, stalls, [&](const Dataset& log) {
    return RunOverFilledLog(log, params, seed, map, progress);
  });
}

}  // namespace evoslam
