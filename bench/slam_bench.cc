// Paper 002's two fitness functions on the Intel log, and the local search that calls one of them
// 310 times a scan.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/io/carmen_reader.h"
#include "common/slam/loop_detector.h"
#include "common/slam/place_matcher.h"
#include "common/slam/rss/global_search_problem.h"
#include "common/slam/rss/local_search.h"
#include "common/slam/rss/rss_slam.h"
#include "common/slam/rss/step_correction_problem.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

const std::filesystem::path kIntelPath = std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";

// The Intel log, read once on first use; nullptr, the benchmark skipped, when it is absent.
const Dataset* IntelOrSkip(benchmark::State& state) {
  static const std::optional<Dataset> log = []() -> std::optional<Dataset> {
    if (!std::filesystem::exists(kIntelPath)) return std::nullopt;
    return ReadCarmen(kIntelPath);
  }();
  if (!log) state.SkipWithError(("data absent: " + kIntelPath.string()).c_str());
  return log ? &*log : nullptr;
}

// A batch of candidates drawn uniformly from the problem's box.
Eigen::MatrixXd RandomBatch(const Problem& problem, Eigen::Index n, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd batch(problem.lower().size(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index g = 0; g < batch.rows(); ++g) {
      batch(g, i) = rng.Uniform(problem.lower()(g), problem.upper()(g));
    }
  }
  return batch;
}

// Times Evaluate on `batch` on state.range(0) threads, then restores the thread count, so that
// OMP_NUM_THREADS still holds for the benchmarks that follow.
void TimeEvaluate(benchmark::State& state, const Problem& problem, const Eigen::MatrixXd& batch) {
  std::vector<double> fitness(problem.objectives() * static_cast<std::size_t>(batch.cols()));
  const int threads = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    problem.Evaluate(batch, fitness);
    benchmark::DoNotOptimize(fitness.data());
  }
  omp_set_num_threads(threads);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * batch.cols()));
}

// One generation of a global search (70 candidates) over the first scans, at their odometry
// poses, re-inserted into the map of the rest of the log. Args: threads, the stretch's scans (over
// 300, eq. 6 re-inserts 300 of them, as for a loop thousands of steps long).
void BM_GlobalSearchEvaluate(benchmark::State& state) {
  const Dataset* log = IntelOrSkip(state);
  if (!log) return;
  const auto stretch = static_cast<std::size_t>(state.range(1));
  constexpr Eigen::Index kCandidates = 70;
  std::vector<Pose2> poses;
  for (const LaserScan& s : log->scans) poses.push_back(s.odometry);
  HitCountGrid base = EmptyMapFor(*log, proto::RssMap{}, LocalSearchParams{});
  for (std::size_t i = stretch; i < log->scans.size(); ++i) base.AddScan(log->scans[i], poses[i]);
  const GlobalSearchParams params;
  const GlobalSearchProblem problem(log->scans, poses, 0, stretch, base, params,
                                    PartitionErrorBounds(params), std::nullopt);
  TimeEvaluate(state, problem, RandomBatch(problem, kCandidates, 1));
  state.counters["cells"] = static_cast<double>(base.width()) * base.height();
}
BENCHMARK(BM_GlobalSearchEvaluate)
    ->ArgNames({"threads", "scans"})
    ->Args({1, 300})
    ->Args({2, 300})
    ->Args({2, 3000})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// One PSO generation of the local search (10 candidates): scan 200 against the map of the 200
// scans before it, at their odometry poses. Arg: threads.
void BM_StepCorrectionEvaluate(benchmark::State& state) {
  const Dataset* log = IntelOrSkip(state);
  if (!log) return;
  constexpr std::size_t kScan = 200;
  constexpr Eigen::Index kCandidates = 10;
  const LocalSearchParams params;
  HitCountGrid map = EmptyMapFor(*log, proto::RssMap{}, params);
  for (std::size_t i = 0; i < kScan; ++i) map.AddScan(log->scans[i], log->scans[i].odometry);
  const StepCorrectionProblem problem(map, log->scans[kScan], log->scans[kScan].odometry,
                                      BaseErrorCube(params), ParseLocalFitness(params.fitness()));
  TimeEvaluate(state, problem, RandomBatch(problem, kCandidates, 1));
}
BENCHMARK(BM_StepCorrectionEvaluate)->Arg(1)->Arg(2)->UseRealTime();

// One match of loop detection: scan 25 of the Intel log, put 0.3 m and 0.1 rad off, against the
// place of scans [0, 51) at their odometry poses. Args: threads, and the window in dm (15, the
// window after a short path; 50, the largest, after a long one).
void BM_PlaceMatcherSearch(benchmark::State& state) {
  const Dataset* log = IntelOrSkip(state);
  if (!log) return;
  constexpr std::size_t kPlace = 51, kScan = 25;
  const LoopDetectionParams params;
  const double window = 0.1 * static_cast<double>(state.range(1));
  std::vector<Pose2> poses;
  for (std::size_t i = 0; i < kPlace; ++i) poses.push_back(log->scans[i].odometry);
  const PlaceMatcher place(std::span(log->scans).first(kPlace), poses, 0.05, 0.1, window);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(log->scans[kScan]);
  const Pose2 start = poses[kScan] * Pose2(0.3, -0.2, 0.1);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        place.Search(points, start, window, params.match_window_rad(), params.rival_distance_m()));
  }
  omp_set_num_threads(threads);
}
BENCHMARK(BM_PlaceMatcherSearch)
    ->Args({1, 15})
    ->Args({2, 15})
    ->Args({1, 50})
    ->Args({2, 50})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The local search with `params` over the first 2000 scans of the Intel log, on OMP_NUM_THREADS
// threads.
void LocalSearchIntel(benchmark::State& state, const LocalSearchParams& params) {
  const Dataset* log = IntelOrSkip(state);
  if (!log) return;
  Dataset first = *log;
  first.scans.resize(2000);
  for (auto _ : state) {
    HitCountGrid map = EmptyMapFor(first, proto::RssMap{}, params);
    benchmark::DoNotOptimize(RunLocalSearch(first, params, 1, map));
  }
  state.counters["scans"] = static_cast<double>(first.scans.size());
}

void BM_LocalSearchIntel(benchmark::State& state) { LocalSearchIntel(state, LocalSearchParams{}); }
BENCHMARK(BM_LocalSearchIntel)->UseRealTime()->Unit(benchmark::kMillisecond);

// The same with the seen space's edge left free: the map also traces every beam.
void BM_LocalSearchIntelEdgeFree(benchmark::State& state) {
  LocalSearchParams params;
  params.set_free_frontier(true);
  LocalSearchIntel(state, params);
}
BENCHMARK(BM_LocalSearchIntelEdgeFree)->UseRealTime()->Unit(benchmark::kMillisecond);

// The whole of 002's algorithm over the first range(0) scans of the Intel log (0: all 13,631),
// on OMP_NUM_THREADS threads. Its speed against the log's own pace is the "x real time" counter;
// its map's cells and the memory the map keeps for them, "map_cells" and "map_bytes".
void BM_RssSlamIntel(benchmark::State& state) {
  const Dataset* log = IntelOrSkip(state);
  if (!log) return;
  proto::SlamParams params;
  params.set_max_scans(static_cast<std::uint32_t>(state.range(0)));
  const std::size_t scans = ScansToMap(*log, params);
  std::optional<RssSlamResult> result;
  for (auto _ : state) {
    result.reset();
    result = RunRssSlam(*log, params);
  }
  const double recorded = log->scans[scans - 1].timestamp - log->scans.front().timestamp;
  state.counters["scans"] = static_cast<double>(scans);
  state.counters["x_real_time"] = benchmark::Counter(
      recorded * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["map_cells"] =
      static_cast<double>(result->map.width()) * static_cast<double>(result->map.height());
  state.counters["map_bytes"] =
      benchmark::Counter(static_cast<double>(result->map.bytes()), benchmark::Counter::kDefaults,
                         benchmark::Counter::kIs1024);
}
BENCHMARK(BM_RssSlamIntel)
    ->Arg(3000)
    ->Arg(0)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace evoslam
