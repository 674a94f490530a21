#include "common/localization/pose_estimator.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "common/engine/archipelago.h"
#include "common/localization/scan_match_problem.h"
#include "common/optim/evolve.h"
#include "common/optim/exhaustive_search.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {

EstimatorKind ParseEstimatorKind(std::string_view name) {
  if (name == "2d") return EstimatorKind::k2D;
  if (name == "3d") return EstimatorKind::k3D;
  throw Error("unknown estimator '" + std::string(name) + "' (expected 2d or 3d)");
}

std::string_view EstimatorKindName(EstimatorKind kind) {
  return kind == EstimatorKind::k2D ? "2d" : "3d";
}

AlgorithmSpec LocalizationAlgorithmDefaults() {
  AlgorithmSpec spec;
  spec.ga.grid_step = 0.01;
  return spec;
}

OptimizerKind ParseOptimizer(std::string_view name, AlgorithmSpec& algorithm) {
  if (name == "island") return OptimizerKind::kIsland;
  if (name == "exhaustive") return OptimizerKind::kExhaustive;
  for (const auto& n : AlgorithmKindNames()) {
    if (n == name) {
      algorithm.kind = ParseAlgorithmKind(name);
      return OptimizerKind::kAlgorithm;
    }
  }
  std::string valid;
  for (const auto& n : OptimizerNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw Error("unknown optimizer '" + std::string(name) + "' (expected one of: " + valid + ")");
}

std::vector<std::string> OptimizerNames() {
  std::vector<std::string> names = AlgorithmKindNames();
  names.emplace_back("island");
  names.emplace_back("exhaustive");
  return names;
}

IslandModelParams IslandModelOf(const EstimatorParams& params) {
  IslandModelParams island;
  island.islands = params.islands;
  island.algorithm = params.algorithm;
  island.migration = params.migration;
  return island;
}

double HeadingsPerScan(const EstimatorParams& params) {
  return 2.0 * std::round(params.heading_half_window / params.heading_step) + 1.0;
}

double LatticePosesPerScan(const EstimatorParams& params) {
  const double side = std::floor(params.window / params.exhaustive_step) + 1.0;
  return side * side * (params.estimator == EstimatorKind::k3D ? HeadingsPerScan(params) : 1.0);
}

void ValidateEstimatorParams(const EstimatorParams& params) {
  if (!(params.window > 0.0)) throw Error("search window must be positive");
  if (!IsFiniteNonNegative(params.fitness.f2_base)) {
    throw Error("F2 tolerance base must be a finite length >= 0");
  }
  if (!IsFiniteNonNegative(params.fitness.f2_slope)) {
    throw Error("F2 tolerance slope must be finite and >= 0");
  }
  if (!IsFiniteNonNegative(params.fitness.f3_cap)) {
    throw Error("F3 cap must be a finite length >= 0 (0: uncapped)");
  }
  if (!(params.heading_half_window >= 0.0) || params.heading_half_window > 3.14159265358979323846) {
    throw Error("heading window must be between 0 and 180 degrees");
  }
  if (!(params.heading_step >= kMinHeadingStep)) {
    throw Error(fmt::format("heading step must be at least {} degrees", Degrees(kMinHeadingStep)));
  }
  if (!(HeadingsPerScan(params) <= kMaxHeadingsPerScan)) {
    throw Error(fmt::format("heading step: {:.0f} headings per scan, more than {:.0f}",
                            HeadingsPerScan(params), kMaxHeadingsPerScan));
  }
  if (!(params.exhaustive_step > 0.0)) throw Error("exhaustive step must be positive");
  if (params.generations == 0) throw Error("generations must be at least 1");
  if (params.optimizer == OptimizerKind::kExhaustive) {
    if (!(LatticePosesPerScan(params) <= kMaxLatticePosesPerScan)) {
      throw Error(fmt::format("exhaustive step: {:.0f} poses per scan, more than {:.0f}",
                              LatticePosesPerScan(params), kMaxLatticePosesPerScan));
    }
    return;
  }
  MakeAlgorithm(params.algorithm);  // throws on parameters the algorithm cannot work with
  if (params.optimizer == OptimizerKind::kIsland) ValidateIslandModelParams(IslandModelOf(params));
}

namespace {

OptimResult BestOf(const Island& island) {
  const Algorithm& a = island.algorithm();
  OptimResult r;
  r.best = a.champion_x();
  r.best_fitness =
      a.champion_f().size() > 0 ? a.champion_f()(0) : std::numeric_limits<double>::quiet_NaN();
  r.evaluations = a.evaluations();
  r.generations = a.generation();
  return r;
}

OptimResult Optimize(const Problem& problem, const EstimatorParams& params,
                     const Eigen::VectorXd& steps, Rng& rng, const SearchRuntime& runtime) {
  const IslandStepper step =
      runtime.step
          ? IslandStepper([&](std::vector<Island>& islands, bool start, std::size_t generations) {
              runtime.step(problem, islands, start, generations);
            })
          : LocalIslandStepper(problem);
  StopCriteria stop;
  stop.max_generations = params.generations;
  switch (params.optimizer) {
    case OptimizerKind::kAlgorithm: {
      // One island run to the end: the same draws as Minimize with this generator.
      std::vector<Island> island;
      island.emplace_back(params.algorithm, stop, rng);
      step(island, true, std::numeric_limits<std::size_t>::max());
      return BestOf(island.front());
    }
    case OptimizerKind::kIsland: {
      Archipelago archipelago = runtime.resume
                                    ? Archipelago::FromCheckpoint(*runtime.resume)
                                    : Archipelago(IslandModelOf(params), stop, rng.NextU64());
      if (!runtime.resume) archipelago.Start(step);
      while (!archipelago.RunEpoch(step)) {
        if (runtime.on_epoch) runtime.on_epoch(archipelago.Checkpoint());
      }
      return archipelago.Best();
    }
    case OptimizerKind::kExhaustive:
      if (runtime.evaluate) {
        return RunExhaustiveSearch(
            problem, steps,
            [&](const Eigen::Ref<const Eigen::MatrixXd>& candidates, std::span<double> fitness) {
              runtime.evaluate(problem, candidates, fitness);
            });
      }
      return RunExhaustiveSearch(problem, steps);
  }
  throw Error("unknown optimizer");
}

}  // namespace

std::unique_ptr<Problem> MakeScanProblem(const RangeRenderer& renderer, const LaserScan& scan,
                                         const Pose2& center, const EstimatorParams& params,
                                         float max_range) {
  ObservedBeams observed = PrepareObservation(scan, max_range);
  if (params.estimator == EstimatorKind::k2D) {
    return std::make_unique<ShiftedScanProblem>(
        renderer, params.fitness,
        MakeShiftLayout(scan, params.heading_half_window, params.heading_step), std::move(observed),
        max_range, center, params.window);
  }
  return std::make_unique<PoseScanProblem>(renderer, params.fitness, scan, std::move(observed),
                                           max_range, center, params.window,
                                           params.heading_half_window);
}

PoseEstimate EstimatePose(const RangeRenderer& renderer, const LaserScan& scan, const Pose2& center,
                          const EstimatorParams& params, float max_range, Rng& rng,
                          const SearchRuntime& runtime) {
  const std::unique_ptr<Problem> problem =
      MakeScanProblem(renderer, scan, center, params, max_range);
  PoseEstimate estimate;
  if (params.estimator == EstimatorKind::k2D) {
    const OptimResult r =
        Optimize(*problem, params, Eigen::Vector2d::Constant(params.exhaustive_step), rng, runtime);
    estimate.pose = static_cast<const ShiftedScanProblem&>(*problem).PoseAt(r.best.head<2>(),
                                                                            &estimate.fitness);
    estimate.evaluations = r.evaluations;
  } else {
    const OptimResult r = Optimize(
        *problem, params,
        Eigen::Vector3d(params.exhaustive_step, params.exhaustive_step, params.heading_step), rng,
        runtime);
    estimate.pose = Pose2(r.best(0), r.best(1), r.best(2));
    estimate.fitness = r.best_fitness;
    estimate.evaluations = r.evaluations;
  }
  return estimate;
}

}  // namespace evoslam
