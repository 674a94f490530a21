#ifndef EVOSLAM_COMMON_LOCALIZATION_POSE_ESTIMATOR_H_
#define EVOSLAM_COMMON_LOCALIZATION_POSE_ESTIMATOR_H_

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/engine/algorithm_spec.h"
#include "common/engine/archipelago.h"
#include "common/engine/migration.h"
#include "common/localization/range_renderer.h"
#include "common/localization/scan_fitness.h"
#include "common/sensor/laser_scan.h"
#include "common/transform/angle_units.h"
#include "common/transform/pose2.h"
#include "common/util/random.h"

namespace evoslam {

// 2D: the optimiser searches position, heading by brute force over the window's shifts.
// 3D: the optimiser searches position and heading together.
enum class EstimatorKind { k2D, k3D };
EstimatorKind ParseEstimatorKind(std::string_view name);  // "2d" | "3d"
std::string_view EstimatorKindName(EstimatorKind kind);

// An engine algorithm on its own (its kind in EstimatorParams::algorithm), an island model of
// that algorithm, or the exhaustive lattice search used as a reference.
enum class OptimizerKind { kAlgorithm, kIsland, kExhaustive };

// "de", "jde", "pso", ... (an engine algorithm), "island" or "exhaustive". For an algorithm name
// the kind is also written to `algorithm`.
OptimizerKind ParseOptimizer(std::string_view name, AlgorithmSpec& algorithm);
std::vector<std::string> OptimizerNames();

// The engine's defaults, with the binary GAs on the papers' 1 cm search grid.
AlgorithmSpec LocalizationAlgorithmDefaults();

struct EstimatorParams {
  FitnessParams fitness;
  EstimatorKind estimator = EstimatorKind::k2D;
  OptimizerKind optimizer = OptimizerKind::kAlgorithm;
  AlgorithmSpec algorithm = LocalizationAlgorithmDefaults();  // alone, or on every island
  std::size_t generations = 25;
  std::size_t islands = 4;
  MigrationParams migration;
  double window = 0.6;  // square search window's side, m
  double heading_half_window = Radians(30.0);
  double heading_step = Radians(0.5);
  double exhaustive_step = 0.01;  // lattice spacing of the reference, m
};

struct PoseEstimate {
  Pose2 pose;
  double fitness = 0.0;
  std::size_t evaluations = 0;
};

// Evaluates a batch of candidates (one per column) of `problem`, writing one fitness each.
using BatchEvaluator =
    std::function<void(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                       std::span<double> fitness)>;
// Starts and evolves islands of `problem`, as IslandStepper does.
using ProblemIslandStepper = std::function<void(
    const Problem& problem, std::vector<Island>& islands, bool start, std::size_t generations)>;

// Where and how one search runs. Empty functions run it here, on local threads; the service
// supplies functions that send the work to its workers, which rebuild the same problem.
struct SearchRuntime {
  ProblemIslandStepper step;
  BatchEvaluator evaluate;
  // Called after every epoch of an island search with its state.
  std::function<void(const ArchipelagoCheckpoint&)> on_epoch;
  // An island search interrupted part-way, to continue instead of starting afresh.
  std::optional<ArchipelagoCheckpoint> resume;
};

// The problem EstimatePose solves: a ShiftedScanProblem (2D) or a PoseScanProblem (3D) over
// the window around `center`. It keeps a reference to `renderer`.
std::unique_ptr<Problem> MakeScanProblem(const RangeRenderer& renderer, const LaserScan& scan,
                                         const Pose2& center, const EstimatorParams& params,
                                         float max_range);

// Finds the pose in the window around `center` whose simulated scan best matches `scan`.
// `max_range` is the range the simulation stops at; observed readings at or beyond it are ignored.
PoseEstimate EstimatePose(const RangeRenderer& renderer, const LaserScan& scan, const Pose2& center,
                          const EstimatorParams& params, float max_range, Rng& rng,
                          const SearchRuntime& runtime = {});

// The island model `--optimizer island` runs: islands of params.algorithm.
IslandModelParams IslandModelOf(const EstimatorParams& params);

// Searches whose size the parameters fix are refused above these, per scan: a step too fine for
// any machine would otherwise exhaust memory or run for days.
inline constexpr double kMaxHeadingsPerScan = 1e5;
inline constexpr double kMaxLatticePosesPerScan = 1e8;
// The 2D estimator matches the scan at each heading of its window, beam by beam, so the step
// must not split a beam's spacing beyond this either.
inline constexpr double kMinHeadingStep = 1e-6;  // radians

// How many headings the search of each scan tries.
double HeadingsPerScan(const EstimatorParams& params);
// How many poses the exhaustive optimizer evaluates for each scan.
double LatticePosesPerScan(const EstimatorParams& params);

// Throws Error naming the offending parameter when params cannot work.
void ValidateEstimatorParams(const EstimatorParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_POSE_ESTIMATOR_H_
