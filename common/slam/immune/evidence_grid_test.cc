#include "common/slam/immune/evidence_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "common/slam/immune/evidence_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::AllUnits;
using testing::EvidenceRoomGeometry;
using testing::Perturbed;
using testing::PreparedScans;
using testing::SimulatedRoomScans;

// A scan of `ranges` over a quarter turn centred straight ahead, as a 10 m laser reads it.
LaserScan FanScan(std::vector<float> ranges) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 4;
  scan.angle_increment = ranges.size() > 1 ? (std::numbers::pi / 2) / (ranges.size() - 1) : 0.0;
  scan.range_min = 0.05;
  scan.range_max = 10.0;
  scan.ranges = std::move(ranges);
  return scan;
}

GridGeometry OpenGeometry() { return GridGeometry(0.05, {-5.025, -5.025}, 201, 201); }

std::size_t CellAt(const EvidenceGrid& grid, double x, double y) {
  return *grid.geometry().CellIndex({x, y});
}

TEST(EvidenceGridTest, WallSeenOftenIsOccupiedAndTheSpaceBeforeItEmpty) {
  const proto::EvidenceGridParams params;
  const PreparedScans prepared(SimulatedRoomScans(), params);
  EvidenceGrid grid(EvidenceRoomGeometry(6, 4), params);
  grid.Add(prepared.placed);
  // The wall y = 0 in the middle of the room, and half a metre in front of it.
  EXPECT_GT(grid.occupied_belief(CellAt(grid, 3.0, 0.0)), 0.5);
  EXPECT_LT(grid.empty_belief(CellAt(grid, 3.0, 0.0)), 0.5);
  EXPECT_GT(grid.empty_belief(CellAt(grid, 3.0, 0.5)), 0.5);
  EXPECT_LT(grid.occupied_belief(CellAt(grid, 3.0, 0.5)), 0.5);
  const EvidenceObjectives f = grid.objectives();
  EXPECT_GT(f.occupied, 0);
  EXPECT_GT(f.empty, f.occupied);
  EXPECT_GT(f.consistency, 0.0);
}

TEST(EvidenceGridTest, NearReadingGivesMoreBeliefThanFarOne) {
  const proto::EvidenceGridParams params;
  const EvidenceScan near(FanScan({0.5f}), params);
  const EvidenceScan far(FanScan({2.5f}), params);
  // A single beam points at angle_min: turned so, it runs along +x from the origin.
  const Pose2 beam_pose(0, 0, std::numbers::pi / 4);
  EvidenceGrid near_turned(OpenGeometry(), params);
  EvidenceGrid far_turned(OpenGeometry(), params);
  near_turned.Add({&near, beam_pose});
  far_turned.Add({&far, beam_pose});
  const double near_occ = near_turned.occupied_belief(CellAt(near_turned, 0.5, 0.0));
  const double far_occ = far_turned.occupied_belief(CellAt(far_turned, 2.5, 0.0));
  EXPECT_GT(near_occ, far_occ);
  EXPECT_GT(far_occ, 0.0);
  EXPECT_LE(near_occ, params.max_belief());
  // Empty readings fall off along the beam too.
  EXPECT_GT(far_turned.empty_belief(CellAt(far_turned, 0.3, 0.0)),
            far_turned.empty_belief(CellAt(far_turned, 2.0, 0.0)));
  EXPECT_EQ(far_turned.occupied_belief(CellAt(far_turned, 2.0, 0.0)), 0.0);
}

TEST(EvidenceGridTest, CutBeamGivesEmptyUpToMaxRangeAndNothingBeyond) {
  proto::EvidenceGridParams params;
  params.set_max_range_m(2.0);
  const EvidenceScan scan(FanScan({4.0f}), params);
  EvidenceGrid grid(OpenGeometry(), params);
  grid.Add({&scan, Pose2(0, 0, std::numbers::pi / 4)});
  EXPECT_GT(grid.empty_units(CellAt(grid, 1.9, 0.0)), 0u);
  for (const double x : {2.1, 3.0, 4.0}) {
    EXPECT_EQ(grid.empty_units(CellAt(grid, x, 0.0)), 0u) << x;
    EXPECT_EQ(grid.occupied_units(CellAt(grid, x, 0.0)), 0u) << x;
  }
  EXPECT_EQ(grid.objectives().occupied, 0);
  for (std::size_t c = 0; c < grid.geometry().cell_count(); ++c) {
    ASSERT_EQ(grid.occupied_units(c), 0u);
  }
}

TEST(EvidenceGridTest, NonReturnsGiveNothing) {
  const proto::EvidenceGridParams params;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const EvidenceScan scan(FanScan({10.0f, 12.0f, 0.01f, nan, 0.0f}), params);
  EXPECT_TRUE(scan.beams().empty());
  EvidenceGrid grid(OpenGeometry(), params);
  grid.Add({&scan, Pose2()});
  EXPECT_EQ(grid.objectives(), EvidenceObjectives{});
  const std::vector<std::uint32_t> units = AllUnits(grid);
  EXPECT_TRUE(std::all_of(units.begin(), units.end(), [](std::uint32_t u) { return u == 0; }));
}

TEST(EvidenceGridTest, BeamStrideKeepsOneBeamInSo) {
  proto::EvidenceGridParams params;
  params.set_beam_stride(3);
  const EvidenceScan scan(FanScan(std::vector<float>(10, 1.0f)), params);
  EXPECT_EQ(scan.beams().size(), 4u);  // beams 0, 3, 6, 9
}

TEST(EvidenceGridTest, ReadingsOutsideTheGeometryAreIgnored) {
  const proto::EvidenceGridParams params;
  const EvidenceScan scan(FanScan(std::vector<float>(30, 2.0f)), params);
  const GridGeometry small(0.05, {-0.5, -0.5}, 20, 20);
  EvidenceGrid grid(small, params);
  grid.Add({&scan, Pose2()});                 // the returns all fall outside
  grid.Add({&scan, Pose2(-30.0, 0.0, 0.0)});  // nothing of it reaches the grid
  grid.Add({&scan, Pose2(std::numeric_limits<double>::quiet_NaN(), 0, 0)});
  EXPECT_EQ(grid.objectives().occupied, 0);
  EXPECT_GT(grid.objectives().empty, 0);
}

TEST(EvidenceGridTest, AddThenRemoveRestoresEveryCell) {
  const proto::EvidenceGridParams params;
  const PreparedScans prepared(SimulatedRoomScans(), params);
  EvidenceGrid grid(EvidenceRoomGeometry(6, 4), params);
  const std::span<const PlacedScan> all(prepared.placed);
  for (std::size_t i = 0; i + 1 < all.size(); ++i) grid.Add(all[i]);
  const EvidenceObjectives before = grid.objectives();
  const std::vector<std::uint32_t> units_before = AllUnits(grid);
  const PlacedScan moved = Perturbed({all.back()}, 0.3, 0.2, 5).front();
  grid.Add(moved);
  EXPECT_NE(grid.objectives(), before);
  grid.Remove(moved);
  EXPECT_EQ(grid.objectives(), before);
  EXPECT_EQ(AllUnits(grid), units_before);
}

TEST(EvidenceGridTest, OrderOfScansDoesNotMatter) {
  const proto::EvidenceGridParams params;
  const PreparedScans prepared(SimulatedRoomScans(), params);
  const std::vector<PlacedScan> placed = Perturbed(prepared.placed, 0.05, 0.05, 2);
  // Wide enough that one scan's beams cross fewer cells than the grid has, so that the grid
  // tracks the cells each touches; adding all at once crosses more, so it recounts every cell.
  const GridGeometry geometry = EvidenceRoomGeometry(6, 4, 5.0);
  double beam_cells = 0.0;
  for (const PlacedScan& p : placed) {
    ASSERT_LT(p.scan->total_range_m() / 0.05, static_cast<double>(geometry.cell_count()));
    beam_cells += p.scan->total_range_m() / 0.05;
  }
  ASSERT_GT(beam_cells, static_cast<double>(geometry.cell_count()));
  EvidenceGrid forward(geometry, params);
  for (const PlacedScan& p : placed) forward.Add(p);
  EvidenceGrid backward(geometry, params);
  for (auto it = placed.rbegin(); it != placed.rend(); ++it) backward.Add(*it);
  std::vector<PlacedScan> shuffled = placed;
  Rng rng(9);
  for (std::size_t i = shuffled.size(); i > 1; --i) {
    std::swap(shuffled[i - 1], shuffled[rng.UniformIndex(i)]);
  }
  EvidenceGrid at_once(geometry, params);
  at_once.Add(shuffled);
  EXPECT_EQ(forward.objectives(), backward.objectives());
  EXPECT_EQ(forward.objectives(), at_once.objectives());
  EXPECT_EQ(forward.totals().consistency, at_once.totals().consistency);
  EXPECT_EQ(AllUnits(forward), AllUnits(backward));
  EXPECT_EQ(AllUnits(forward), AllUnits(at_once));
  // Taking them all back, one by one or at once, leaves nothing.
  for (const PlacedScan& p : shuffled) forward.Remove(p);
  at_once.Remove(placed);
  EXPECT_EQ(forward.objectives(), EvidenceObjectives{});
  EXPECT_EQ(at_once.objectives(), EvidenceObjectives{});
}

TEST(EvidenceGridTest, TotalsEqualTheSumOfCellScores) {
  const proto::EvidenceGridParams params;
  const PreparedScans prepared(SimulatedRoomScans(), params);
  EvidenceGrid grid(EvidenceRoomGeometry(6, 4), params);
  for (const PlacedScan& p : Perturbed(prepared.placed, 0.1, 0.1, 3)) grid.Add(p);
  EvidenceTotals sum;
  for (std::size_t c = 0; c < grid.geometry().cell_count(); ++c) sum.Add(grid.score(c), 1);
  EXPECT_EQ(sum.consistency, grid.totals().consistency);
  EXPECT_EQ(sum.occupied, grid.totals().occupied);
  EXPECT_EQ(sum.empty, grid.totals().empty);
  // f2 and f3 count exactly the cells whose beliefs pass count_above.
  std::int64_t occupied = 0, empty = 0;
  for (std::size_t c = 0; c < grid.geometry().cell_count(); ++c) {
    occupied += grid.occupied_belief(c) > params.count_above();
    empty += grid.empty_belief(c) > params.count_above();
  }
  EXPECT_EQ(occupied, grid.objectives().occupied);
  EXPECT_EQ(empty, grid.objectives().empty);
}

TEST(EvidenceGridTest, ConsistencyPrefersTheTruePoses) {
  const proto::EvidenceGridParams params;
  const PreparedScans prepared(SimulatedRoomScans(), params);
  EvidenceGrid truth(EvidenceRoomGeometry(6, 4), params);
  truth.Add(prepared.placed);
  for (const std::uint64_t seed : {1, 2, 3}) {
    EvidenceGrid perturbed(EvidenceRoomGeometry(6, 4), params);
    perturbed.Add(Perturbed(prepared.placed, 0.1, 0.05, seed));
    EXPECT_LT(truth.objectives().consistency, perturbed.objectives().consistency) << seed;
  }
  // One scan turned by 5 degrees doubles the walls it sees.
  std::vector<PlacedScan> one_turned = prepared.placed;
  one_turned[3].pose = one_turned[3].pose * Pose2(0, 0, 5 * std::numbers::pi / 180);
  EvidenceGrid turned(EvidenceRoomGeometry(6, 4), params);
  turned.Add(one_turned);
  EXPECT_LT(truth.objectives().consistency, turned.objectives().consistency);
}

TEST(EvidenceGridTest, GeometryForHoldsEveryScan) {
  const proto::EvidenceGridParams params;
  const PreparedScans prepared(SimulatedRoomScans(), params);
  const GridGeometry g = EvidenceGeometryFor(prepared.placed, params);
  EXPECT_EQ(g.resolution(), params.cell_size_m());
  for (const PlacedScan& p : prepared.placed) {
    for (const EvidenceBeam& b : p.scan->beams()) {
      const Eigen::Vector2d end = p.pose * Eigen::Vector2d(b.range_m * b.x, b.range_m * b.y);
      ASSERT_TRUE(g.CellIndex(end).has_value());
    }
  }
  EXPECT_THROW(EvidenceGeometryFor({}, params), Error);
  std::vector<PlacedScan> bad = prepared.placed;
  bad[0].pose = Pose2(std::numeric_limits<double>::infinity(), 0, 0);
  EXPECT_THROW(EvidenceGeometryFor(bad, params), Error);
}

TEST(EvidenceGridTest, RejectsGeometryOfNoOrTooManyCells) {
  const proto::EvidenceGridParams params;
  EXPECT_THROW(EvidenceGrid(GridGeometry(), params), Error);
  EXPECT_THROW(EvidenceGrid(GridGeometry(0.05, {0, 0}, 1 << 14, 1 << 14), params), Error);
}

}  // namespace
}  // namespace evoslam
