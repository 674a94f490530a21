#include "common/slam/immune/evidence_overlay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "common/slam/immune/evidence_testing.h"

namespace evoslam {
namespace {

using testing::EvidenceRoomGeometry;
using testing::Perturbed;
using testing::PreparedScans;
using testing::SimulatedRoomScans;

// The objectives of a grid built anew from `placed` with scans [begin, end) moved to `moved`.
EvidenceTotals Rebuilt(std::vector<PlacedScan> placed, std::size_t begin,
                       const std::vector<PlacedScan>& moved,
                       const proto::EvidenceGridParams& params) {
  std::copy(moved.begin(), moved.end(), placed.begin() + static_cast<std::ptrdiff_t>(begin));
  EvidenceGrid grid(EvidenceRoomGeometry(6, 4), params);
  for (const PlacedScan& p : placed) grid.Add(p);
  return grid.totals();
}

void ExpectSame(const EvidenceTotals& a, const EvidenceTotals& b) {
  EXPECT_EQ(a.consistency, b.consistency);
  EXPECT_EQ(a.occupied, b.occupied);
  EXPECT_EQ(a.empty, b.empty);
}

// Scans of the simulated room at their true poses, and the base grid of them all.
class EvidenceOverlayTest : public ::testing::Test {
 protected:
  EvidenceOverlayTest() : prepared_(SimulatedRoomScans(0.2), params_), placed_(prepared_.placed) {
    base_.Add(placed_);
  }

  std::vector<PlacedScan> Window(std::size_t begin, std::size_t size) const {
    return {placed_.begin() + static_cast<std::ptrdiff_t>(begin),
            placed_.begin() + static_cast<std::ptrdiff_t>(begin + size)};
  }

  const proto::EvidenceGridParams params_;
  const PreparedScans prepared_;
  const std::vector<PlacedScan>& placed_;
  EvidenceGrid base_{EvidenceRoomGeometry(6, 4), params_};
};

TEST_F(EvidenceOverlayTest, ScoreEqualsTheGridRebuiltWithTheChange) {
  EvidenceOverlay overlay(base_);
  for (const std::uint64_t seed : {1, 2, 3}) {
    const std::size_t begin = 5 * seed;
    const std::vector<PlacedScan> window = Window(begin, 8);
    const std::vector<PlacedScan> moved = Perturbed(window, 0.2, 0.1, seed);
    const EvidenceTotals scored = overlay.ScoreTotals(window, moved);
    ExpectSame(scored, Rebuilt(placed_, begin, moved, params_));
    EXPECT_EQ(overlay.Score(window, moved), scored.objectives());
  }
  // The base is as it was, and an empty change scores as the base.
  ExpectSame(overlay.ScoreTotals({}, {}), base_.totals());
  ExpectSame(overlay.ScoreTotals(placed_, placed_), base_.totals());
}

TEST_F(EvidenceOverlayTest, StretchTakenOutOnceScoresEveryCandidate) {
  EvidenceOverlay overlay(base_);
  const std::size_t begin = 20;
  std::vector<PlacedScan> window = Window(begin, 10);
  overlay.SetRemoved(window);
  window.clear();  // SetRemoved keeps nothing of the span it is given
  for (const std::uint64_t seed : {4, 5, 6}) {
    const std::vector<PlacedScan> moved = Perturbed(Window(begin, 10), 0.3, 0.2, seed);
    ExpectSame(overlay.ScoreAddedTotals(moved), Rebuilt(placed_, begin, moved, params_));
  }
  // Nothing taken out: only what is put in counts.
  overlay.SetRemoved({});
  EvidenceGrid more(EvidenceRoomGeometry(6, 4), params_);
  more.Add(placed_);
  more.Add(placed_[0]);
  ExpectSame(overlay.ScoreAddedTotals({&placed_[0], 1}), more.totals());
}

TEST_F(EvidenceOverlayTest, ScansReachingPastTheGridMatchTheGrid) {
  EvidenceOverlay overlay(base_);
  const std::vector<PlacedScan> window = Window(0, 4);
  std::vector<PlacedScan> moved = window;
  moved[0].pose = Pose2(-2.5, 2.0, 0.0);   // the laser off the grid, its beams coming in
  moved[1].pose = Pose2(6.5, 3.9, 0.7);    // in a corner of the grid, beams leaving it
  moved[2].pose = Pose2(-40.0, 9.0, 0.0);  // nowhere near
  moved[3].pose = Pose2(std::nan(""), 1.0, 0.0);
  ExpectSame(overlay.ScoreTotals(window, moved), Rebuilt(placed_, 0, moved, params_));
}

TEST_F(EvidenceOverlayTest, RemovingOnlyOrAddingOnlyMatchesTheGrid) {
  const std::span<const PlacedScan> all(placed_);
  EvidenceGrid some(EvidenceRoomGeometry(6, 4), params_);
  some.Add(all.subspan(0, 10));
  EvidenceOverlay overlay(some);
  EvidenceGrid fewer(EvidenceRoomGeometry(6, 4), params_);
  fewer.Add(all.subspan(0, 6));
  ExpectSame(overlay.ScoreTotals(all.subspan(6, 4), {}), fewer.totals());
  EvidenceGrid more(EvidenceRoomGeometry(6, 4), params_);
  more.Add(all.subspan(0, 14));
  ExpectSame(overlay.ScoreTotals({}, all.subspan(10, 4)), more.totals());
}

TEST_F(EvidenceOverlayTest, OverlaysShareOneBaseAcrossThreads) {
  const std::vector<PlacedScan> window = Window(0, 6);
  std::vector<std::vector<PlacedScan>> candidates;
  std::vector<EvidenceObjectives> expected;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    candidates.push_back(Perturbed(window, 0.2, 0.1, seed));
    expected.push_back(EvidenceOverlay(base_).Score(window, candidates.back()));
  }
  std::vector<std::vector<EvidenceObjectives>> got(2);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < got.size(); ++t) {
    threads.emplace_back([&, t] {
      EvidenceOverlay overlay(base_);
      for (int round = 0; round < 3; ++round) {
        for (const auto& c : candidates) got[t].push_back(overlay.Score(window, c));
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (const auto& results : got) {
    ASSERT_EQ(results.size(), 3 * expected.size());
    for (std::size_t i = 0; i < results.size(); ++i) {
      EXPECT_EQ(results[i], expected[i % expected.size()]);
    }
  }
}

}  // namespace
}  // namespace evoslam
