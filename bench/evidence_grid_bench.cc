// Paper 004's evidence grid on the Intel log: the whole map a candidate trajectory renders, and
// the overlay that scores a candidate moving a window of scans against a shared base.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/io/carmen_reader.h"
#include "common/slam/immune/evidence_grid.h"
#include "common/slam/immune/evidence_overlay.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// The Intel log's scans prepared for the grid and placed at the log's poses, made once on first
// use; nullptr, the benchmark skipped, when the log is absent.
struct IntelEvidence {
  proto::EvidenceGridParams params;
  std::vector<EvidenceScan> scans;
  std::vector<PlacedScan> placed;
  GridGeometry geometry;
};

const IntelEvidence* IntelEvidenceOrSkip(benchmark::State& state) {
  static const std::filesystem::path path =
      std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";
  static const std::optional<IntelEvidence> intel = []() -> std::optional<IntelEvidence> {
    if (!std::filesystem::exists(path)) return std::nullopt;
    const Dataset log = ReadCarmen(path);
    IntelEvidence e;
    e.scans.reserve(log.scans.size());
    for (const LaserScan& s : log.scans) e.scans.emplace_back(s, e.params);
    for (std::size_t i = 0; i < e.scans.size(); ++i) {
      e.placed.push_back({&e.scans[i], log.scans[i].pose});
    }
    e.geometry = EvidenceGeometryFor(e.placed, e.params);
    return e;
  }();
  if (!intel) state.SkipWithError(("data absent: " + path.string()).c_str());
  return intel ? &*intel : nullptr;
}

// A fitness evaluation's map: a fresh grid with every scan of the log (13,631) at its pose.
void BM_EvidenceGridWholeLog(benchmark::State& state) {
  const IntelEvidence* intel = IntelEvidenceOrSkip(state);
  if (!intel) return;
  for (auto _ : state) {
    EvidenceGrid grid(intel->geometry, intel->params);
    grid.Add(intel->placed);
    benchmark::DoNotOptimize(grid.objectives());
  }
  state.counters["scans"] = static_cast<double>(intel->placed.size());
  state.counters["cells"] = static_cast<double>(intel->geometry.cell_count());
}
BENCHMARK(BM_EvidenceGridWholeLog)->Unit(benchmark::kMillisecond);

// The base grid of the whole log, a window of scans of it (from scan 5,000) and eight candidates
// moving it: each pose moved by up to 10 cm and 2 degrees.
struct WindowMoves {
  EvidenceGrid base;
  std::span<const PlacedScan> window;
  std::vector<std::vector<PlacedScan>> candidates;

  WindowMoves(const IntelEvidence& intel, std::size_t size)
      : base(intel.geometry, intel.params),
        window(std::span<const PlacedScan>(intel.placed).subspan(5000, size)) {
    base.Add(intel.placed);
    Rng rng(4);
    for (int c = 0; c < 8; ++c) {
      std::vector<PlacedScan>& moved = candidates.emplace_back(window.begin(), window.end());
      for (PlacedScan& p : moved) {
        p.pose = Pose2(p.pose.x() + rng.Uniform(-0.1, 0.1), p.pose.y() + rng.Uniform(-0.1, 0.1),
                       p.pose.theta() + rng.Uniform(-0.035, 0.035));
      }
    }
  }
};

// One candidate scored against the base: the window of state.range(0) scans taken out at its
// poses in the base and put in at the candidate's (Score traces both).
void BM_EvidenceOverlayWindow(benchmark::State& state) {
  const IntelEvidence* intel = IntelEvidenceOrSkip(state);
  if (!intel) return;
  const WindowMoves moves(*intel, static_cast<std::size_t>(state.range(0)));
  EvidenceOverlay overlay(moves.base);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(overlay.Score(moves.window, moves.candidates[i++ & 7]));
  }
  state.counters["scans"] = static_cast<double>(moves.window.size());
}
BENCHMARK(BM_EvidenceOverlayWindow)->Arg(100)->Unit(benchmark::kMillisecond);

// The same candidates with the window taken out once (SetRemoved), as a search scoring many
// candidates for one window does: each call traces only the candidate's scans.
void BM_EvidenceOverlayWindowAdded(benchmark::State& state) {
  const IntelEvidence* intel = IntelEvidenceOrSkip(state);
  if (!intel) return;
  const WindowMoves moves(*intel, static_cast<std::size_t>(state.range(0)));
  EvidenceOverlay overlay(moves.base);
  overlay.SetRemoved(moves.window);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(overlay.ScoreAdded(moves.candidates[i++ & 7]));
  }
  state.counters["scans"] = static_cast<double>(moves.window.size());
}
BENCHMARK(BM_EvidenceOverlayWindowAdded)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace evoslam
