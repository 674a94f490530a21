// The estimator: F3 candidate evaluations, one scan at POP 25 / GEN 25, and the 219-scan
// s-shaped corridor run the speed goal names.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "bench/corridor_scene.h"
#include "common/io/carmen_reader.h"
#include "common/localization/localizer.h"
#include "common/localization/scan_match_problem.h"
#include "common/localization/segment_renderer.h"
#include "common/transform/angle_units.h"

namespace evoslam {
namespace {

// F3 candidates per second: batches of 25 positions in a 60 cm window, 361 beams, +-30 degrees.
// Arg: threads.
void BM_F3Candidates(benchmark::State& state) {
  const CorridorScene& scene = Corridor();
  const LaserScan& scan = scene.log.scans[100];
  const Pose2 center = *scan.true_pose;
  const SegmentRenderer renderer(TemporaryMap(scene.world.map, center.translation(), 8.5));
  const ShiftLayout layout = MakeShiftLayout(scan, Radians(30.0), Radians(0.5));
  const ShiftedScanProblem problem(renderer, FitnessParams{}, layout,
                                   PrepareObservation(scan, 8.0f), 8.0f, center, 0.6);
  Rng rng(3);
  Eigen::MatrixXd batch(2, 25);
  for (Eigen::Index i = 0; i < 25; ++i) {
    batch.col(i) =
        center.translation() + Eigen::Vector2d(rng.Uniform(-0.3, 0.3), rng.Uniform(-0.3, 0.3));
  }
  std::vector<double> fitness(25);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    problem.Evaluate(batch, fitness);
    benchmark::DoNotOptimize(fitness.data());
  }
  omp_set_num_threads(omp_get_num_procs());
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * 25));
  state.counters["beams"] = static_cast<double>(scan.size());
  state.counters["shifts"] = static_cast<double>(layout.shifts);
}
BENCHMARK(BM_F3Candidates)->Arg(1)->Arg(2)->UseRealTime();

// One scan localized with DE/rand/1/exp, POP 25, GEN 25 (650 evaluations). Arg: threads.
void BM_LocalizeOneScan(benchmark::State& state) {
  const CorridorScene& scene = Corridor();
  const LaserScan& scan = scene.log.scans[100];
  const Pose2 center = *scene.log.scans[99].true_pose;
  const MapModel map(scene.world.map);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  std::uint64_t seed = 0;
  for (auto _ : state) {
    const auto renderer = map.LocalRenderer(center.translation(), 8.0 + 0.43);
    Rng rng(++seed);
    benchmark::DoNotOptimize(EstimatePose(*renderer, scan, center, EstimatorParams{}, 8.0f, rng));
  }
  omp_set_num_threads(omp_get_num_procs());
}
BENCHMARK(BM_LocalizeOneScan)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

// The speed goal: all 219 scans of the s-shaped corridor, POP 25 / GEN 25. Arg: threads.
void BM_LocalizeCorridor(benchmark::State& state) {
  const CorridorScene& scene = Corridor();
  const MapModel map(scene.world.map);
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(Localize(map, scene.log, LocalizeOptions{}));
  omp_set_num_threads(omp_get_num_procs());
  state.counters["scans"] = static_cast<double>(scene.log.scans.size());
}
BENCHMARK(BM_LocalizeCorridor)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

// Parsing the 13,631-scan Intel log (bzip2) end to end.
void BM_ReadIntelLog(benchmark::State& state) {
  const std::filesystem::path path = std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("data absent: " + path.string()).c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(ReadCarmen(path));
}
BENCHMARK(BM_ReadIntelLog)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace evoslam

BENCHMARK_MAIN();
