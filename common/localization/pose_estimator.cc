#include "common/localization/pose_estimator.h"

#include <cmath>
#include <string>

#include "common/localization/scan_match_problem.h"
#include "common/optim/evolve.h"
#include "common/optim/exhaustive_search.h"
#include "common/util/error.h"

namespace evoslam {

EstimatorKind ParseEstimatorKind(std::string_view name) {
  if (name == "2d") return EstimatorKind::k2D;
  if (name == "3d") return EstimatorKind::k3D;
  throw Error("unknown estimator '" + std::string(name) + "' (expected 2d or 3d)");
}

std::string_view EstimatorKindName(EstimatorKind kind) {
  return kind == EstimatorKind::k2D ? "2d" : "3d";
}

OptimizerKind ParseOptimizerKind(std::string_view name) {
  if (name == "de") return OptimizerKind::kDe;
  if (name == "pso") return OptimizerKind::kPso;
  if (name == "exhaustive") return OptimizerKind::kExhaustive;
  throw Error("unknown optimizer '" + std::string(name) + "' (expected de, pso or exhaustive)");
}

std::string_view OptimizerKindName(OptimizerKind kind) {
  switch (kind) {
    case OptimizerKind::kDe:
      return "de";
    case OptimizerKind::kPso:
      return "pso";
    case OptimizerKind::kExhaustive:
      return "exhaustive";
  }
  return "unknown";
}

void ValidateEstimatorParams(const EstimatorParams& params) {
  if (!(params.window > 0.0)) throw Error("search window must be positive");
  if (!(params.heading_half_window >= 0.0) || params.heading_half_window > 3.14159265358979323846) {
    throw Error("heading window must be between 0 and 180 degrees");
  }
  if (!(params.heading_step > 0.0)) throw Error("heading step must be positive");
  if (!(params.exhaustive_step > 0.0)) throw Error("exhaustive step must be positive");
  if (params.generations == 0) throw Error("generations must be at least 1");
  if (params.optimizer == OptimizerKind::kDe && params.de.population < 4) {
    throw Error("DE population must be at least 4");
  }
  if (params.optimizer == OptimizerKind::kPso && params.pso.particles < 2) {
    throw Error("PSO needs at least 2 particles");
  }
  if (params.optimizer == OptimizerKind::kPso && !(params.pso.vmax_fraction > 0.0)) {
    throw Error("PSO velocity clamp must be positive, or particles never move");
  }
}

namespace {

OptimResult Optimize(const Problem& problem, const EstimatorParams& params,
                     const Eigen::VectorXd& steps, Rng& rng) {
  StopCriteria stop;
  stop.max_generations = params.generations;
  switch (params.optimizer) {
    case OptimizerKind::kDe: {
      DifferentialEvolution de(params.de);
      return Minimize(problem, de, stop, rng);
    }
    case OptimizerKind::kPso: {
      ParticleSwarm pso(params.pso);
      return Minimize(problem, pso, stop, rng);
    }
    case OptimizerKind::kExhaustive:
      return RunExhaustiveSearch(problem, steps);
  }
  throw Error("unknown optimizer");
}

}  // namespace

PoseEstimate EstimatePose(const RangeRenderer& renderer, const LaserScan& scan, const Pose2& center,
                          const EstimatorParams& params, float max_range, Rng& rng) {
  ObservedBeams observed = PrepareObservation(scan, max_range);
  PoseEstimate estimate;
  if (params.estimator == EstimatorKind::k2D) {
    const ShiftLayout layout =
        MakeShiftLayout(scan, params.heading_half_window, params.heading_step);
    const ShiftedScanProblem problem(renderer, params.fitness, layout, std::move(observed),
                                     max_range, center, params.window);
    const OptimResult r =
        Optimize(problem, params, Eigen::Vector2d::Constant(params.exhaustive_step), rng);
    estimate.pose = problem.PoseAt(r.best.head<2>(), &estimate.fitness);
    estimate.evaluations = r.evaluations;
  } else {
    const PoseScanProblem problem(renderer, params.fitness, scan, std::move(observed), max_range,
                                  center, params.window, params.heading_half_window);
    const OptimResult r = Optimize(
        problem, params,
        Eigen::Vector3d(params.exhaustive_step, params.exhaustive_step, params.heading_step), rng);
    estimate.pose = Pose2(r.best(0), r.best(1), r.best(2));
    estimate.fitness = r.best_fitness;
    estimate.evaluations = r.evaluations;
  }
  return estimate;
}

}  // namespace evoslam
