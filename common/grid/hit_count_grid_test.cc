#include "common/grid/hit_count_grid.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <set>
#include <type_traits>

#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(HitCountGridTest, CountsObservationsAndKeepsTheWholeMapSumsUpToDate) {
  HitCountGrid grid(0.1, Eigen::Vector2d(-1.0, -1.0), 20, 20);
  EXPECT_EQ(grid.MeanPerOccupied(), 0.0);
  EXPECT_TRUE(grid.Add({0.05, 0.05}));
  EXPECT_TRUE(grid.Add({0.01, 0.09}));  // the same cell
  EXPECT_TRUE(grid.Add({0.55, -0.35}));
  EXPECT_FALSE(grid.Add({1.0, 0.0}));  // the upper bound is outside
  EXPECT_FALSE(grid.Add({std::nan(""), 0.0}));
  const auto cell = grid.WorldToCell({0.05, 0.05});
  ASSERT_TRUE(cell);
  EXPECT_EQ(*cell, Eigen::Vector2i(10, 10));
  EXPECT_EQ(grid.count(10, 10), 2u);
  EXPECT_EQ(grid.total(), 3u);
  EXPECT_EQ(grid.occupied(), 2u);
  EXPECT_DOUBLE_EQ(grid.MeanPerOccupied(), 1.5);
  // Taking observations back, never below zero.
  EXPECT_TRUE(grid.Add({0.55, -0.35}, -5));
  EXPECT_EQ(grid.total(), 2u);
  EXPECT_EQ(grid.occupied(), 1u);
  EXPECT_THROW(grid.count(20, 0), std::out_of_range);
}

TEST(HitCountGridTest, TheRunningSumsAgreeWithAFullCountAfterRandomChanges) {
  HitCountGrid grid(0.5, Eigen::Vector2d::Zero(), 8, 6);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> x(-0.5, 4.5), y(-0.5, 3.5);
  std::uniform_int_distribution<int> delta(-2, 3);
  for (int i = 0; i < 2000; ++i) grid.Add({x(gen), y(gen)}, delta(gen));
  const HitCountGrid::WindowSums all = grid.Window(-5, -5, 100, 100);
  EXPECT_EQ(all.total, grid.total());
  EXPECT_EQ(all.occupied, grid.occupied());
  std::uint64_t total = 0, occupied = 0;
  for (int cy = 0; cy < 6; ++cy) {
    for (int cx = 0; cx < 8; ++cx) {
      total += grid.count(cx, cy);
      occupied += grid.count(cx, cy) > 0;
    }
  }
  EXPECT_EQ(total, grid.total());
  EXPECT_EQ(occupied, grid.occupied());
  const auto part = grid.Window(2, 1, 5, 3);
  std::uint64_t part_total = 0;
  for (int cy = 1; cy < 3; ++cy) {
    for (int cx = 2; cx < 5; ++cx) part_total += grid.count(cx, cy);
  }
  EXPECT_EQ(part.total, part_total);
}

TEST(HitCountGridTest, ACellIsOccupiedExactlyWhileItsCountIsAboveZero) {
  HitCountGrid grid(0.5, Eigen::Vector2d::Zero(), 40, 6);  // 240 cells: several words of bits
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> x(0.0, 20.0), y(0.0, 3.0);
  std::uniform_int_distribution<int> delta(-3, 2);
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector2d point(x(gen), y(gen));
    grid.Add(point, delta(gen));
    const std::size_t cell = *grid.CellIndex(point);
    ASSERT_EQ(grid.occupied(cell), grid.count(cell) > 0) << "after change " << i;
  }
  for (std::size_t cell = 0; cell < 240; ++cell) {
    EXPECT_EQ(grid.occupied(cell), grid.count(cell) > 0) << "cell " << cell;
  }
}

TEST(HitCountGridTest, AScanAddsItsReturnsWhereTheyEndAndTakesThemBackExactly) {
  HitCountGrid grid(0.05, Eigen::Vector2d(-5.0, -5.0), 200, 200);
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 2;
  scan.range_min = 0.1;
  scan.range_max = 8.0;
  scan.ranges = {1.0, 2.0, 8.0};  // the last is no return
  const Pose2 pose(1.0, 1.0, std::numbers::pi / 2);
  EXPECT_EQ(grid.AddScan(scan, pose), 0u);
  EXPECT_EQ(grid.total(), 2u);
  // Beam 0 points along the robot's -y, which is world +x; beam 1 along world +y.
  const auto right = grid.WorldToCell({2.01, 1.01}), up = grid.WorldToCell({1.01, 3.01});
  ASSERT_TRUE(right && up);
  EXPECT_EQ(grid.count(right->x(), right->y()), 1u);
  EXPECT_EQ(grid.count(up->x(), up->y()), 1u);
  grid.AddScan(scan, pose, -1);
  EXPECT_EQ(grid.total(), 0u);
  EXPECT_EQ(grid.occupied(), 0u);
  scan.ranges = {7.0, 0.5, 0.0};  // (4, -7) is off the grid, (4.5, 0) on it, 0 no return
  EXPECT_EQ(grid.AddScan(scan, Pose2(4.0, 0.0, 0.0)), 1u);  // one end point beyond the grid
}

// The map of a log whose odometry drifted far, at the search's 6 cm: 180 x 180 m, 9 million cells
// (36 MB of counts were they all kept). A scan's counts keep the tiles its end points fall in.
TEST(HitCountGridTest, KeepsCountsOnlyForTheTilesItsScansCover) {
  HitCountGrid grid(0.06, Eigen::Vector2d(-90.0, -90.0), 3000, 3000);
  const std::size_t bits = (3000 * 3000 + 63) / 64 * sizeof(std::uint64_t);
  const std::size_t table = 47 * 47 * sizeof(std::vector<std::uint32_t>);
  EXPECT_EQ(grid.bytes(), bits + table);
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 179;
  scan.range_max = 50.0;
  scan.ranges.assign(180, 4.0);  // a round room of 4 m
  grid.AddScan(scan, Pose2(1.0, 2.0, 0.3));
  std::set<std::pair<int, int>> tiles;
  for (const Eigen::Vector2d& p : ReturnPoints(scan)) {
    const Eigen::Vector2i cell = *grid.WorldToCell(Pose2Frame(Pose2(1.0, 2.0, 0.3)) * p);
    tiles.emplace(cell.x() / TiledCounts::kTileSide, cell.y() / TiledCounts::kTileSide);
  }
  EXPECT_EQ(grid.bytes(), bits + table + tiles.size() * TiledCounts::kTileCells * 4);
  EXPECT_LT(grid.bytes(), 2'000'000u);
  // Taking the scan back leaves the tiles, and the counts zero.
  grid.AddScan(scan, Pose2(1.0, 2.0, 0.3), -1);
  EXPECT_EQ(grid.total(), 0u);
  EXPECT_EQ(grid.Window(0, 0, 3000, 3000).occupied, 0u);
}

// One beam along world +x from (0.51, 0.51) to a wall at x = 1.51, one along +y that returns
// nothing within the laser's 1.2 m: the cells each ray crosses, and the edge of them.
TEST(HitCountGridTest, TrackedRaysMarkTheCellsTheyCrossAndLeaveTheEdgeFree) {
  HitCountGrid grid(0.1, Eigen::Vector2d(0.0, 0.0), 40, 40);
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = std::numbers::pi / 2;
  scan.range_min = 0.1;
  scan.range_max = 1.2;
  scan.ranges = {1.0, 1.2};  // the second is no return
  const Pose2 pose(0.51, 0.51, 0.0);
  const auto index = [&](double x, double y) { return *grid.CellIndex({x, y}); };

  grid.AddScan(scan, pose);  // without ray tracking nothing is crossed, nothing is an edge
  EXPECT_FALSE(grid.tracks_rays());
  EXPECT_FALSE(grid.crossed(index(1.05, 0.55)));
  EXPECT_FALSE(grid.Frontier(index(1.05, 0.65)));

  HitCountGrid tracked(0.1, Eigen::Vector2d(0.0, 0.0), 40, 40);
  tracked.TrackRays();
  tracked.AddScan(scan, pose);
  for (double x = 0.55; x < 1.5; x += 0.1) EXPECT_TRUE(tracked.crossed(index(x, 0.55))) << x;
  EXPECT_FALSE(tracked.crossed(index(1.55, 0.55)));  // the wall's cell: hit, not crossed
  EXPECT_TRUE(tracked.occupied(index(1.55, 0.55)));
  for (double y = 0.55; y < 1.7; y += 0.1) EXPECT_TRUE(tracked.crossed(index(0.55, y))) << y;
  EXPECT_FALSE(tracked.crossed(index(0.55, 1.75)));  // where the range ends
  EXPECT_FALSE(tracked.crossed(index(1.05, 1.05)));

  // Beside a crossed cell and not seen: the edge. Behind the wall, or away from every ray: not.
  EXPECT_TRUE(tracked.Frontier(index(1.05, 0.65)));
  EXPECT_TRUE(tracked.Frontier(index(0.55, 1.75)));
  EXPECT_FALSE(tracked.Frontier(index(1.65, 0.55)));
  EXPECT_FALSE(tracked.Frontier(index(1.05, 1.05)));
  EXPECT_FALSE(tracked.Frontier(index(1.05, 0.55)));  // crossed
  EXPECT_FALSE(tracked.Frontier(index(1.55, 0.55)));  // occupied

  // A point on the edge makes no cell occupied when the edge is free, one when it is not.
  CellSet cells;
  HitCountGrid::Insertion counted, free;
  const std::vector<Eigen::Vector2d> edge{{1.05, 0.65}};
  tracked.CountInsertion(Pose2Frame(Pose2()), edge, cells, counted);
  cells.Clear();
  tracked.CountInsertion(Pose2Frame(Pose2()), edge, cells, free, true);
  EXPECT_EQ(counted.fresh, 1u);
  EXPECT_EQ(free.fresh, 0u);
  EXPECT_EQ(free.inside, 1u);

  // Two scans cross the same cells; taking one back leaves the other's rays, taking both back
  // leaves none.
  tracked.AddScan(scan, pose);
  tracked.AddScan(scan, pose, -1);
  EXPECT_TRUE(tracked.crossed(index(1.05, 0.55)));
  EXPECT_TRUE(tracked.Frontier(index(1.05, 0.65)));
  tracked.AddScan(scan, pose, -1);
  EXPECT_EQ(tracked.occupied(), 0u);
  EXPECT_FALSE(tracked.crossed(index(1.05, 0.55)));
  EXPECT_FALSE(tracked.Frontier(index(1.05, 0.65)));
}

// A set for the cells of a grid of `grid_cells` cells, of either kind.
template <typename Cells>
Cells CellsFor(std::size_t grid_cells) {
  if constexpr (std::is_same_v<Cells, GridCellSet>) {
    return GridCellSet(grid_cells);
  } else {
    return CellSet();  // room for few: it grows as cells come
  }
}

template <typename Cells>
class CellSetsTest : public ::testing::Test {};
using CellSetTypes = ::testing::Types<CellSet, GridCellSet>;
TYPED_TEST_SUITE(CellSetsTest, CellSetTypes);

TYPED_TEST(CellSetsTest, CountingAnInsertionGivesWhatAddingTheScansWouldChange) {
  HitCountGrid grid(0.1, Eigen::Vector2d(-4.0, -3.0), 80, 60);
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> range(0.2f, 6.0f);
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 180;
  scan.range_min = 0.1;
  scan.range_max = 5.5;  // the longer ranges are no returns
  for (int i = 0; i < 181; ++i) scan.ranges.push_back(range(gen));
  grid.AddScan(scan, Pose2(0.5, 0.0, 0.3));
  // Two more scans counted as one insertion, some of their end points off the grid.
  const Pose2 a(0.6, 0.1, 0.35), b(2.0, -1.0, -2.0);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(scan);
  TypeParam cells = CellsFor<TypeParam>(80 * 60);
  HitCountGrid::Insertion sums;
  grid.CountInsertion(Pose2Frame(a), points, cells, sums);
  grid.CountInsertion(Pose2Frame(b), points, cells, sums);
  HitCountGrid added = grid;
  const std::size_t outside = added.AddScan(scan, a) + added.AddScan(scan, b);
  EXPECT_GT(outside, 0u);
  EXPECT_EQ(sums.inside, 2 * points.size() - outside);
  EXPECT_EQ(sums.inside, added.total() - grid.total());
  EXPECT_EQ(sums.fresh, added.occupied() - grid.occupied());
  std::size_t hit = 0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 80; ++x) {
      const bool changed = added.count(x, y) != grid.count(x, y);
      hit += changed;
      EXPECT_EQ(cells.Contains(static_cast<std::size_t>(y) * 80 + x), changed);
    }
  }
  EXPECT_EQ(cells.size(), hit);
}

TYPED_TEST(CellSetsTest, HoldWhatAStdSetHoldsThroughGrowingAndClearing) {
  constexpr std::size_t kLast = HitCountGrid::kMaxCells - 1;  // the largest index a grid has
  TypeParam cells = CellsFor<TypeParam>(kLast + 1);
  std::set<std::size_t> want;
  std::mt19937 gen(5);
  std::uniform_int_distribution<std::size_t> cell(0, 3000);
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 2000; ++i) {
      const std::size_t c = round == 2 && i == 0 ? kLast : cell(gen);
      ASSERT_EQ(cells.Insert(c), want.insert(c).second) << c;
    }
    EXPECT_EQ(cells.size(), want.size());
    std::size_t wrong = 0;
    for (std::size_t c = 0; c <= 3000; ++c) wrong += cells.Contains(c) != want.contains(c);
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(cells.Contains(kLast), round == 2);
    if (round < 2) {
      const std::size_t held = *want.begin();
      cells.Clear();
      want.clear();
      EXPECT_EQ(cells.size(), 0u);
      EXPECT_FALSE(cells.Contains(held));
    }
  }
}

TEST(HitCountGridTest, RefusesGridsThatCannotBe) {
  EXPECT_THROW(HitCountGrid(0.0, Eigen::Vector2d::Zero(), 1, 1), Error);
  EXPECT_THROW(HitCountGrid(0.1, Eigen::Vector2d(std::nan(""), 0), 1, 1), Error);
  EXPECT_THROW(HitCountGrid(0.1, Eigen::Vector2d::Zero(), 0, 1), Error);
  EXPECT_THROW(HitCountGrid(0.1, Eigen::Vector2d::Zero(), 1 << 15, 1 << 15), Error);
}

}  // namespace
}  // namespace evoslam
