// Paper 004's method on the Intel log: what one candidate of a window's search costs, its scans
// put in at the candidate's poses on the map of the scans before the window.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/io/carmen_reader.h"
#include "common/slam/immune/evidence_grid.h"
#include "common/slam/immune/trajectory_segments.h"
#include "common/slam/immune/trajectory_window_problem.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// The log's scans prepared for the grid, its segments at the log's poses, and the map of every
// scan before scan 5,000; made once, nullptr when the log is absent.
struct IntelWindows {
  proto::ImmuneParams params;
  Dataset log;
  std::vector<Pose2> poses;
  std::vector<EvidenceScan> scans;
  std::unique_ptr<SegmentedTrajectory> trajectory;
  std::unique_ptr<EvidenceGrid> base;
  std::size_t first_segment = 0;  // the first segment from scan 5,000 on
};

const IntelWindows* IntelWindowsOrSkip(benchmark::State& state) {
  static const std::filesystem::path path =
      std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";
  static const std::unique_ptr<IntelWindows> intel = []() -> std::unique_ptr<IntelWindows> {
    if (!std::filesystem::exists(path)) return nullptr;
    auto w = std::make_unique<IntelWindows>();
    w->log = ReadCarmen(path);
    for (const LaserScan& s : w->log.scans) {
      w->poses.push_back(s.pose);
      w->scans.emplace_back(s, w->params.evidence());
    }
    w->trajectory = std::make_unique<SegmentedTrajectory>(
        w->poses, CutSegments(w->poses, {}, w->params.segments()));
    while (w->trajectory->segments()[w->first_segment].first < 5000) ++w->first_segment;
    std::vector<PlacedScan> placed;
    for (std::size_t k = 0; k < w->trajectory->segments()[w->first_segment].first; ++k) {
      placed.push_back({&w->scans[k], w->poses[k]});
    }
    w->base = std::make_unique<EvidenceGrid>(EvidenceGeometryFor(placed, w->params.evidence(), 5.0),
                                             w->params.evidence());
    w->base->Add(placed);
    return w;
  }();
  if (!intel) state.SkipWithError(("data absent: " + path.string()).c_str());
  return intel.get();
}

// One candidate of a window of state.range(0) segments from scan 5,000 (Intel's segments of
// 1.5 m hold some 40 scans), evaluated alone on one thread: its poses, then its scans put in on
// the base through an overlay.
void BM_ImmuneWindowCandidate(benchmark::State& state) {
  const IntelWindows* intel = IntelWindowsOrSkip(state);
  if (!intel) return;
  const auto segments = static_cast<std::size_t>(state.range(0));
  const TrajectoryWindowProblem problem(
      {.trajectory = intel->trajectory.get(),
       .scans = intel->scans,
       .base = intel->base.get(),
       .first_segment = intel->first_segment,
       .segments = segments,
       .from = intel->poses[intel->trajectory->segments()[intel->first_segment].first],
       .key_points = {}},
      intel->params);
  Rng rng(3);
  Eigen::MatrixXd candidates(problem.dimension(), 8);
  for (Eigen::Index c = 0; c < 8; ++c) {
    for (Eigen::Index g = 0; g < candidates.rows(); ++g) {
      candidates(g, c) = std::round(rng.Uniform(-2.0, 2.0));  // a few cm and degrees
    }
  }
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  std::vector<double> fitness(problem.objectives());
  Eigen::Index i = 0;
  for (auto _ : state) {
    problem.Evaluate(candidates.col(i++ & 7), fitness);
    benchmark::DoNotOptimize(fitness.data());
  }
  omp_set_num_threads(threads);
  state.counters["scans"] = static_cast<double>(problem.last_scan() - problem.first_scan() + 1);
}
BENCHMARK(BM_ImmuneWindowCandidate)->Arg(3)->Arg(26)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace evoslam
