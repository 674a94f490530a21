#include "common/grid/occupancy_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "common/util/error.h"
#include "common/util/infinity.h"

namespace evoslam {
namespace {

LaserScan MakeScan(double angle_min, double angle_increment, std::vector<float> ranges) {
  LaserScan scan;
  scan.angle_min = angle_min;
  scan.angle_increment = angle_increment;
  scan.range_min = 0.01;
  scan.range_max = 30.0;
  scan.ranges = std::move(ranges);
  return scan;
}

// Ray parameters (metres along the unit ray) where the ray is inside the box, if it meets it.
bool RayBox(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& lo,
            const Eigen::Vector2d& hi, double& enter, double& exit) {
  enter = -kInfinity;
  exit = kInfinity;
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    const double t0 = (lo[a] - o[a]) / d[a];
    const double t1 = (hi[a] - o[a]) / d[a];
    enter = std::max(enter, std::min(t0, t1));
    exit = std::min(exit, std::max(t0, t1));
  }
  return enter <= exit;
}

std::vector<Eigen::Vector2i> OccupiedCells(const OccupancyGrid& grid) {
  std::vector<Eigen::Vector2i> cells;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.IsOccupied(x, y)) cells.emplace_back(x, y);
    }
  }
  return cells;
}

// Reference ray cast: the nearest entry into any of the occupied cells, checking every one.
double BruteForceCast(const OccupancyGrid& grid, const std::vector<Eigen::Vector2i>& occupied,
                      const Eigen::Vector2d& origin, double angle, double max_range) {
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  double best = max_range;
  for (const Eigen::Vector2i& cell : occupied) {
    const Eigen::Vector2d lo = grid.origin() + grid.resolution() * cell.cast<double>();
    const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(grid.resolution());
    double enter = 0.0;
    double exit = 0.0;
    if (RayBox(origin, d, lo, hi, enter, exit) && exit >= 0.0) {
      best = std::min(best, std::max(enter, 0.0));
    }
  }
  return best;
}

TEST(OccupancyGridTest, RejectsBadConstruction) {
  EXPECT_THROW(OccupancyGrid(0.0, {0, 0}, 10, 10), Error);
  EXPECT_THROW(OccupancyGrid(-0.1, {0, 0}, 10, 10), Error);
  EXPECT_THROW(OccupancyGrid(std::numeric_limits<double>::quiet_NaN(), {0, 0}, 10, 10), Error);
  EXPECT_THROW(OccupancyGrid(0.1, {kInfinity, 0}, 10, 10), Error);
  EXPECT_THROW(OccupancyGrid(0.1, {0, 0}, 0, 10), Error);
  EXPECT_THROW(OccupancyGrid(0.1, {0, 0}, 10, -1), Error);
  EXPECT_THROW(OccupancyGrid(0.1, {0, 0}, 1 << 14, 1 << 14), Error);
}

TEST(OccupancyGridTest, CellWorldConversions) {
  const OccupancyGrid grid(0.5, {-2.0, 1.0}, 8, 4);
  EXPECT_TRUE(grid.CellToWorld(0, 0).isApprox(Eigen::Vector2d(-1.75, 1.25)));
  EXPECT_TRUE(grid.CellToWorld(7, 3).isApprox(Eigen::Vector2d(1.75, 2.75)));
  EXPECT_EQ(grid.WorldToCell({-2.0, 1.0}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(grid.WorldToCell({-1.49, 2.99}), Eigen::Vector2i(1, 3));
  EXPECT_EQ(grid.WorldToCell({1.99, 1.0}), Eigen::Vector2i(7, 0));
  EXPECT_FALSE(grid.WorldToCell({2.0, 1.5}));
  EXPECT_FALSE(grid.WorldToCell({0.0, 0.99}));
  EXPECT_FALSE(grid.WorldToCell({std::numeric_limits<double>::quiet_NaN(), 1.5}));
  EXPECT_FALSE(grid.WorldToCell({1e300, 1.5}));
  EXPECT_TRUE(grid.max_corner().isApprox(Eigen::Vector2d(2.0, 3.0)));
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(grid.WorldToCell(grid.CellToWorld(x, y)), Eigen::Vector2i(x, y));
  }
  EXPECT_TRUE(grid.Contains(7, 3));
  EXPECT_FALSE(grid.Contains(8, 0));
  EXPECT_FALSE(grid.Contains(0, -1));
  EXPECT_THROW(grid.hits(8, 0), std::out_of_range);
  EXPECT_THROW(grid.state(-1, 0), std::out_of_range);
}

TEST(OccupancyGridTest, LogOddsFollowNamedModel) {
  OccupancyGrid grid(0.1, {0, 0}, 2, 1);
  EXPECT_EQ(grid.state(0, 0), CellState::kUnknown);
  EXPECT_DOUBLE_EQ(grid.probability(0, 0), 0.5);
  const double hit = std::log(kHitProbability / (1 - kHitProbability));
  const double miss = std::log(kMissProbability / (1 - kMissProbability));
  LaserScan scan = MakeScan(0.0, 0.0, {0.1f});
  grid.InsertScan(scan, Pose2(0.05, 0.05, 0.0));  // miss in cell 0, hit in cell 1
  grid.InsertScan(scan, Pose2(0.05, 0.05, 0.0));
  grid.InsertScan(scan, Pose2(0.05, 0.05, 0.0));
  EXPECT_EQ(grid.misses(0, 0), 3u);
  EXPECT_EQ(grid.hits(1, 0), 3u);
  EXPECT_NEAR(grid.log_odds(0, 0), 3 * miss, 1e-12);
  EXPECT_NEAR(grid.log_odds(1, 0), 3 * hit, 1e-12);
  EXPECT_NEAR(grid.probability(1, 0), 1.0 / (1.0 + std::exp(-3 * hit)), 1e-12);
  EXPECT_EQ(grid.state(0, 0), CellState::kFree);
  EXPECT_EQ(grid.state(1, 0), CellState::kOccupied);
}

TEST(OccupancyGridTest, SetCellGivesRequestedStates) {
  OccupancyGrid grid(0.1, {0, 0}, 3, 1);
  grid.SetCell(0, 0, CellState::kOccupied);
  grid.SetCell(1, 0, CellState::kFree);
  grid.SetCell(2, 0, CellState::kOccupied);
  grid.SetCell(2, 0, CellState::kUnknown);
  EXPECT_EQ(grid.state(0, 0), CellState::kOccupied);
  EXPECT_EQ(grid.state(1, 0), CellState::kFree);
  EXPECT_EQ(grid.state(2, 0), CellState::kUnknown);
  EXPECT_GT(grid.probability(0, 0), kOccupiedThreshold);
  EXPECT_LT(grid.probability(1, 0), kFreeThreshold);
  EXPECT_EQ(grid.hits(2, 0) + grid.misses(2, 0), 0u);
}

// Does the segment a-b touch the closed box [lo, hi]?
bool SegmentTouchesBox(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double length = (b - a).norm();
  double enter = 0.0;
  double exit = 0.0;
  const double slack = 1e-9;
  return RayBox(a, (b - a) / length, lo.array() - slack, hi.array() + slack, enter, exit) &&
         exit >= 0.0 && enter <= length;
}

TEST(OccupancyGridTest, InsertScanHitsWallAndMissesBefore) {
  const double res = 0.1;
  OccupancyGrid grid(res, {0.0, 0.0}, 60, 40);
  const Pose2 pose(1.05, 2.05, 0.0);
  const double wall_x = 4.05;  // inside cell column 40
  std::vector<float> ranges;
  const double angle_min = -0.5;
  const double increment = 0.05;
  for (int i = 0; i <= 20; ++i) {
    ranges.push_back(static_cast<float>((wall_x - pose.x()) / std::cos(angle_min + i * increment)));
  }
  const LaserScan scan = MakeScan(angle_min, increment, ranges);
  grid.InsertScan(scan, pose);

  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> beams;
  std::set<std::pair<int, int>> end_cells;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double a = scan.angle(i);
    const Eigen::Vector2d end =
        pose.translation() + scan.ranges[i] * Eigen::Vector2d(std::cos(a), std::sin(a));
    beams.emplace_back(pose.translation(), end);
    const auto cell = grid.WorldToCell(end);
    ASSERT_TRUE(cell);
    EXPECT_EQ(cell->x(), 40);
    end_cells.insert({cell->x(), cell->y()});
    EXPECT_GE(grid.hits(cell->x(), cell->y()), 1u);
    EXPECT_EQ(grid.misses(cell->x(), cell->y()), 0u);
    // Every cell a dense walk along the beam visits before the end cell is a miss.
    for (double s = 0.0; s < 1.0; s += 1e-4) {
      const auto c = grid.WorldToCell(pose.translation() + s * (end - pose.translation()));
      ASSERT_TRUE(c);
      if (*c == *cell) break;
      EXPECT_GE(grid.misses(c->x(), c->y()), 1u) << c->transpose();
    }
  }
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.hits(x, y) > 0) {
        EXPECT_TRUE(end_cells.count({x, y})) << x << "," << y;
      }
      if (x > 40) {
        EXPECT_EQ(grid.hits(x, y) + grid.misses(x, y), 0u);
      }
      if (grid.misses(x, y) == 0) continue;
      EXPECT_EQ(grid.hits(x, y), 0u);
      // A miss only where some beam actually crosses the cell.
      const Eigen::Vector2d lo = grid.origin() + res * Eigen::Vector2d(x, y);
      const bool crossed = std::any_of(beams.begin(), beams.end(), [&](const auto& beam) {
        return SegmentTouchesBox(beam.first, beam.second, lo, lo.array() + res);
      });
      EXPECT_TRUE(crossed) << x << "," << y;
    }
  }
  EXPECT_FALSE(grid.has_distance_field());
  // The central beam runs along row 20.
  for (int x = 10; x < 40; ++x) EXPECT_GE(grid.misses(x, 20), 1u) << x;
  EXPECT_EQ(grid.state(40, 20), CellState::kOccupied);
}

TEST(OccupancyGridTest, NonReturnsClearUpToFreeRangeWithoutHits) {
  OccupancyGrid grid(0.1, {0.0, 0.0}, 100, 10);
  LaserScan scan = MakeScan(0.0, 0.0, {30.0f});  // at range_max: no return
  grid.InsertScan(scan, Pose2(0.05, 0.55, 0.0));
  const int free_cells = static_cast<int>(std::floor((0.05 + kNoReturnFreeRange) / 0.1));
  for (int x = 0; x < 100; ++x) {
    EXPECT_EQ(grid.hits(x, 5), 0u);
    EXPECT_EQ(grid.misses(x, 5) > 0, x <= free_cells) << x;
  }
  OccupancyGrid other(0.1, {0.0, 0.0}, 100, 10);
  scan.ranges = {std::numeric_limits<float>::quiet_NaN()};
  other.InsertScan(scan, Pose2(0.05, 0.55, 0.0));
  scan.ranges = {0.005f};  // below range_min
  other.InsertScan(scan, Pose2(0.05, 0.55, 0.0));
  for (int x = 0; x < 100; ++x) EXPECT_EQ(other.hits(x, 5) + other.misses(x, 5), 0u);
  scan.ranges = {std::numeric_limits<float>::infinity()};
  other.InsertScan(scan, Pose2(0.05, 0.55, 0.0));
  EXPECT_EQ(other.misses(free_cells, 5), 1u);
  EXPECT_EQ(other.misses(free_cells + 1, 5), 0u);
}

TEST(OccupancyGridTest, BeamsOutsideGridAreClipped) {
  OccupancyGrid grid(0.1, {0.0, 0.0}, 10, 10);
  // Sensor left of the grid, beam crossing it and ending beyond: misses only, no hit.
  grid.InsertScan(MakeScan(0.0, 0.0, {3.0f}), Pose2(-1.0, 0.55, 0.0));
  for (int x = 0; x < 10; ++x) {
    EXPECT_EQ(grid.misses(x, 5), 1u);
    EXPECT_EQ(grid.hits(x, 5), 0u);
  }
  // Sensor outside, beam ending inside: misses from the edge, hit at the end.
  grid.InsertScan(MakeScan(0.0, 0.0, {1.5f}), Pose2(-1.0, 0.25, 0.0));
  EXPECT_EQ(grid.hits(5, 2), 1u);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(grid.misses(x, 2), 1u);
  // Beam that never meets the grid.
  grid.InsertScan(MakeScan(0.0, 0.0, {3.0f}), Pose2(-1.0, 5.0, 0.0));
  EXPECT_THROW(grid.InsertScan(MakeScan(0.0, 0.0, {1.0f}), Pose2(kInfinity, 0.0, 0.0)), Error);
}

TEST(OccupancyGridTest, FromScansFitsAllPoints) {
  const std::vector<LaserScan> scans{
      MakeScan(0.0, std::numbers::pi / 2, {3.0f, 2.0f, 1.0f, 1.5f}),
      MakeScan(0.0, 0.0, {0.7f}),
  };
  const std::vector<Pose2> poses{Pose2(0.2, 0.1, 0.0), Pose2(-0.5, 4.0, std::numbers::pi)};
  const double margin = 0.5;
  const double res = 0.1;
  const OccupancyGrid grid = OccupancyGrid::FromScans(scans, poses, res, margin);
  std::vector<Eigen::Vector2d> ends;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (std::size_t i = 0; i < scans[s].size(); ++i) {
      const double a = poses[s].theta() + scans[s].angle(i);
      ends.push_back(poses[s].translation() +
                     scans[s].ranges[i] * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
  }
  // Nominally (3.2, 0.1), (0.2, 2.1), (-0.8, 0.1), (0.2, -1.4), (-1.2, 4.0).
  const Eigen::Vector2d lo(-1.2, -1.4);
  const Eigen::Vector2d hi(3.2, 4.0);
  EXPECT_NEAR(grid.min_corner().x(), lo.x() - margin, 1e-6);
  EXPECT_NEAR(grid.min_corner().y(), lo.y() - margin, 1e-6);
  EXPECT_GE(grid.max_corner().x(), hi.x() + margin - 1e-6);
  EXPECT_GE(grid.max_corner().y(), hi.y() + margin - 1e-6);
  EXPECT_LE(grid.max_corner().x(), hi.x() + margin + res + 1e-6);
  EXPECT_LE(grid.max_corner().y(), hi.y() + margin + res + 1e-6);
  EXPECT_TRUE(grid.has_distance_field());
  for (const auto& end : ends) {
    const auto cell = grid.WorldToCell(end);
    ASSERT_TRUE(cell) << end.transpose();
    EXPECT_EQ(grid.state(cell->x(), cell->y()), CellState::kOccupied) << end.transpose();
  }
  // Zero margin: the extreme points still fall inside.
  const OccupancyGrid tight = OccupancyGrid::FromScans(scans, poses, res, 0.0);
  for (const auto& end : ends) EXPECT_TRUE(tight.WorldToCell(end)) << end.transpose();
}

TEST(OccupancyGridTest, ReturnsOfOneScanDoNotEraseEachOther) {
  OccupancyGrid grid(0.1, {0.0, 0.0}, 20, 10);
  // Beam 0 ends in cell (10, 0); beam 1 runs along row 0 through it to cell (15, 0).
  LaserScan scan = MakeScan(0.0, 0.0, {1.0f, 1.5f});
  grid.InsertScan(scan, Pose2(0.05, 0.05, 0.0));
  EXPECT_EQ(grid.hits(10, 0), 1u);
  EXPECT_EQ(grid.misses(10, 0), 0u);
  EXPECT_EQ(grid.hits(15, 0), 1u);
  EXPECT_EQ(grid.misses(12, 0), 1u);
  EXPECT_EQ(grid.misses(5, 0), 2u);
  // A later scan's beam through the same cell does count.
  scan.ranges = {1.5f};
  grid.InsertScan(scan, Pose2(0.05, 0.05, 0.0));
  EXPECT_EQ(grid.misses(10, 0), 1u);
}

// A robot driving down a long corridor sees each stretch of wall twice: nearly square on as it
// passes, and at a grazing angle from far back, when its rays run along the wall's row of cells
// before they end further on. Real poses and ranges are a centimetre or two off, so a wall's hits
// spread over the two rows it lies between while the grazing rays cross both. The walls must
// survive that, or a map of a corridor driven once comes out broken into dots.
TEST(OccupancyGridTest, CorridorWallsSeenAtGrazingAnglesStayWhole) {
  constexpr double kRes = 0.05;
  constexpr double kHalfWidth = 1.0;  // walls at y = ±1, on cell boundaries
  constexpr double kEndWall = 40.0;
  OccupancyGrid grid(kRes, {-1.0, -1.5}, 860, 60);
  std::mt19937 rng(7);
  std::normal_distribution<double> lateral(0.0, 0.01);
  std::normal_distribution<double> heading(0.0, 0.5 * std::numbers::pi / 180.0);
  std::normal_distribution<double> range_noise(0.0, 0.01);
  for (int step = 0; step <= 300; ++step) {  // 10 cm apart
    const double x = 0.1 * step;
    const Pose2 pose(x, lateral(rng), heading(rng));
    // The true rays start at the true pose (x, 0, 0); the scan is inserted at the noisy one.
    std::vector<float> ranges;
    for (int i = 0; i <= 180; ++i) {
      const double a = (i - 90) * std::numbers::pi / 180.0;
      const double c = std::cos(a), s = std::sin(a);
      double r = c > 0.0 ? (kEndWall - x) / c : kInfinity;
      if (s != 0.0) r = std::min(r, kHalfWidth / std::abs(s));
      ranges.push_back(static_cast<float>(r + range_noise(rng)));
    }
    LaserScan scan = MakeScan(-std::numbers::pi / 2, std::numbers::pi / 180.0, ranges);
    scan.range_max = 50.0;
    grid.InsertScan(scan, pose);
  }
  int whole = 0, columns = 0;
  for (int column = 0; column < 400; ++column) {  // x from 5 to 25 m
    for (const double y : {-kHalfWidth, kHalfWidth}) {
      const auto cell = grid.WorldToCell({5.0 + (column + 0.5) * kRes, y});
      ASSERT_TRUE(cell);
      ++columns;
      whole += grid.IsOccupied(cell->x(), cell->y()) || grid.IsOccupied(cell->x(), cell->y() - 1);
    }
  }
  EXPECT_EQ(whole, columns);
}

TEST(OccupancyGridTest, FromScansRejectsBadInput) {
  const std::vector<LaserScan> scans{MakeScan(0.0, 0.1, {1.0f})};
  const std::vector<Pose2> poses{Pose2()};
  const std::vector<Pose2> two{Pose2(), Pose2()};
  EXPECT_THROW(OccupancyGrid::FromScans(scans, two, 0.1, 0.0), Error);
  EXPECT_THROW(OccupancyGrid::FromScans({}, {}, 0.1, 0.0), Error);
  EXPECT_THROW(OccupancyGrid::FromScans(scans, poses, 0.0, 0.0), Error);
  EXPECT_THROW(OccupancyGrid::FromScans(scans, poses, 0.1, -1.0), Error);
  const std::vector<LaserScan> two_scans{scans[0], scans[0]};
  const std::vector<Pose2> spread{Pose2(), Pose2(1e5, 1e5, 0.0)};
  EXPECT_THROW(OccupancyGrid::FromScans(two_scans, spread, 0.05, 0.0), Error);
}

// The extent of 1e5 m with one scan at each end needs 2e6 x 2e6 cells of 5 cm; 2^26 cells hold
// 8192 x 8192, which 1e5 m fills at 12.8 m (2^8 x 5 cm) but not at 6.4 m.
TEST(OccupancyGridTest, FittingResolutionDoublesUntilTheScansFit) {
  const std::vector<LaserScan> scans{MakeScan(0.0, 0.1, {1.0f}), MakeScan(0.0, 0.1, {1.0f})};
  const std::vector<Pose2> spread{Pose2(), Pose2(1e5, 1e5, 0.0)};
  const double fitting = OccupancyGrid::FittingResolution(scans, spread, 0.05, 0.0);
  EXPECT_DOUBLE_EQ(fitting, 0.05 * 256);
  // Half as fine does not fit (the refusal comes before any cell is allocated).
  EXPECT_THROW(OccupancyGrid::FromScans(scans, spread, fitting / 2, 0.0), Error);
  // What fits already keeps its resolution; bad input is refused as FromScans refuses it.
  const std::vector<Pose2> near{Pose2(), Pose2(3.0, 4.0, 0.0)};
  EXPECT_DOUBLE_EQ(OccupancyGrid::FittingResolution(scans, near, 0.05, 1.0), 0.05);
  EXPECT_THROW(OccupancyGrid::FittingResolution(scans, near, 0.0, 1.0), Error);
  EXPECT_THROW(OccupancyGrid::FittingResolution(scans, {near.data(), 1}, 0.05, 1.0), Error);
}

// A grid of the given size with random occupied, free and unknown cells.
OccupancyGrid RandomGrid(std::mt19937& rng, double occupied_fraction) {
  std::uniform_int_distribution<int> size(1, 40);
  std::uniform_real_distribution<double> res(0.02, 0.5);
  std::uniform_real_distribution<double> offset(-3.0, 3.0);
  OccupancyGrid grid(res(rng), {offset(rng), offset(rng)}, size(rng), size(rng));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const double r = u(rng);
      grid.SetCell(x, y,
                   r < occupied_fraction         ? CellState::kOccupied
                   : r < 0.5 + occupied_fraction ? CellState::kFree
                                                 : CellState::kUnknown);
    }
  }
  return grid;
}

TEST(OccupancyGridTest, CastRayMatchesBruteForceOnRandomGrids) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double fractions[] = {0.0, 0.003, 0.02, 0.1, 0.3, 0.7};
  int hits = 0;
  int rays = 0;
  for (int trial = 0; trial < 100; ++trial) {
    OccupancyGrid grid = RandomGrid(rng, fractions[trial % 6]);
    const Eigen::Vector2d lo = grid.min_corner();
    const Eigen::Vector2d extent = grid.max_corner() - lo;
    std::vector<std::tuple<Eigen::Vector2d, double, double>> cases;
    for (int i = 0; i < 150; ++i) {
      // Origins mostly on the grid, some around it.
      const Eigen::Vector2d origin = lo + Eigen::Vector2d(extent.x() * (1.4 * u(rng) - 0.2),
                                                          extent.y() * (1.4 * u(rng) - 0.2));
      double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
      if (i % 10 == 0) angle = (i / 10 % 4) * std::numbers::pi / 2;  // axis-aligned
      const double max_range = i % 7 == 0 ? kInfinity : 1.5 * extent.norm() * u(rng);
      cases.emplace_back(origin, angle, max_range);
    }
    const std::vector<Eigen::Vector2i> occupied = OccupiedCells(grid);
    for (int pass = 0; pass < 2; ++pass) {
      ASSERT_EQ(grid.has_distance_field(), pass == 1);
      for (const auto& [origin, angle, max_range] : cases) {
        const double expected = BruteForceCast(grid, occupied, origin, angle, max_range);
        const double got = grid.CastRay(origin, angle, max_range);
        if (std::isinf(expected)) {
          EXPECT_TRUE(std::isinf(got));
        } else {
          ASSERT_NEAR(got, expected, 1e-9)
              << "trial " << trial << " pass " << pass << " origin " << origin.transpose()
              << " angle " << angle << " max " << max_range;
        }
        hits += expected < max_range;
        ++rays;
      }
      grid.UpdateDistanceField();
    }
  }
  // The cases must exercise both outcomes.
  EXPECT_GT(hits, rays / 4);
  EXPECT_LT(hits, rays * 3 / 4);
}

TEST(OccupancyGridTest, CastRayOnLargeSparseGridMatchesBruteForce) {
  // Long free stretches make the distance-field leaps long; a few scattered cells must still
  // stop every ray at the right place.
  std::mt19937 rng(3);
  OccupancyGrid grid(0.05, {-4.0, -3.0}, 200, 160);
  std::uniform_int_distribution<int> cx(0, 199);
  std::uniform_int_distribution<int> cy(0, 159);
  for (int i = 0; i < 60; ++i) grid.SetCell(cx(rng), cy(rng), CellState::kOccupied);
  grid.UpdateDistanceField();
  const std::vector<Eigen::Vector2i> occupied = OccupiedCells(grid);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 10000; ++i) {
    const Eigen::Vector2d origin(-4.0 + 10.0 * u(rng), -3.0 + 8.0 * u(rng));
    const double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    ASSERT_NEAR(grid.CastRay(origin, angle, 8.0),
                BruteForceCast(grid, occupied, origin, angle, 8.0), 1e-9)
        << origin.transpose() << " " << angle;
  }
}

TEST(OccupancyGridTest, CastRayOnRoomsMatchesBruteForce) {
  // Rooms with doorways and clutter: long leaps along corridors, short ones near walls.
  OccupancyGrid grid(0.05, {0.0, 0.0}, 240, 160);
  const auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    for (double s = 0.0; s <= 1.0; s += 1e-3) {
      if (const auto cell = grid.WorldToCell(a + s * (b - a))) {
        grid.SetCell(cell->x(), cell->y(), CellState::kOccupied);
      }
    }
  };
  wall({0.2, 0.2}, {11.8, 0.2});
  wall({11.8, 0.2}, {11.8, 7.8});
  wall({11.8, 7.8}, {0.2, 7.8});
  wall({0.2, 7.8}, {0.2, 0.2});
  wall({4.0, 0.2}, {4.0, 3.0});
  wall({4.0, 4.0}, {4.0, 7.8});
  wall({8.0, 0.2}, {8.0, 5.0});
  wall({4.0, 5.5}, {7.0, 5.5});
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector2d a(0.5 + 11.0 * u(rng), 0.5 + 7.0 * u(rng));
    wall(a, a + Eigen::Vector2d(0.5 * u(rng), 0.5 * u(rng)));
  }
  grid.UpdateDistanceField();
  const std::vector<Eigen::Vector2i> occupied = OccupiedCells(grid);
  for (int i = 0; i < 800; ++i) {
    const Eigen::Vector2d origin(0.3 + 11.4 * u(rng), 0.3 + 7.4 * u(rng));
    const double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    ASSERT_NEAR(grid.CastRay(origin, angle, 8.0),
                BruteForceCast(grid, occupied, origin, angle, 8.0), 1e-9)
        << origin.transpose() << " " << angle;
  }
}

TEST(OccupancyGridTest, CastRayHitsWallAtAnalyticDistance) {
  const double res = 0.05;
  OccupancyGrid grid(res, {0.0, 0.0}, 240, 200);
  // A slanted wall through (9, 1) and (7, 9), rasterised by sampling it densely.
  const Eigen::Vector2d a(9.0, 1.0);
  const Eigen::Vector2d b(7.0, 9.0);
  for (double s = 0.0; s <= 1.0; s += 1e-4) {
    const auto cell = grid.WorldToCell(a + s * (b - a));
    grid.SetCell(cell->x(), cell->y(), CellState::kOccupied);
  }
  grid.UpdateDistanceField();
  const Eigen::Vector2d origin(2.0, 5.0);
  const Eigen::Vector2d normal = Eigen::Vector2d(b.y() - a.y(), a.x() - b.x()).normalized();
  // From atan2(-4, 7) to atan2(4, 5): the rays that meet the wall between its end points.
  for (double angle = -0.5; angle <= 0.65; angle += 0.01) {
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    const double analytic = (a - origin).dot(normal) / d.dot(normal);
    const double got = grid.CastRay(origin, angle, 20.0);
    // The cell holding the wall point is entered at most a cell diagonal before it, along the
    // ray no further than that over the cosine of the incidence.
    EXPECT_LE(got, analytic + 1e-9) << angle;
    EXPECT_GE(got, analytic - std::numbers::sqrt2 * res / std::abs(d.dot(normal))) << angle;
  }
  // A wall on a cell boundary is hit exactly.
  OccupancyGrid column(res, {0.0, 0.0}, 240, 200);
  for (int y = 0; y < 200; ++y) column.SetCell(150, y, CellState::kOccupied);
  column.UpdateDistanceField();
  for (double angle = -0.7; angle <= 0.7; angle += 0.05) {
    EXPECT_NEAR(column.CastRay(origin, angle, 20.0), (7.5 - 2.0) / std::cos(angle), 1e-9);
  }
  EXPECT_DOUBLE_EQ(column.CastRay(origin, std::numbers::pi, 20.0), 20.0);
  EXPECT_DOUBLE_EQ(column.CastRay(origin, 0.0, 3.0), 3.0);
}

TEST(OccupancyGridTest, DirectionCastEqualsAngleCast) {
  OccupancyGrid grid(0.1, {0.0, 0.0}, 50, 40);
  for (int x = 10; x < 40; ++x) grid.SetCell(x, 30, CellState::kOccupied);
  for (int y = 5; y < 30; ++y) grid.SetCell(35, y, CellState::kOccupied);
  grid.UpdateDistanceField();
  const Eigen::Vector2d origin(1.2, 1.7);
  for (double angle = -3.1; angle < 3.1; angle += 0.013) {
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    ASSERT_EQ(grid.CastRay(origin, d, 6.0), grid.CastRay(origin, angle, 6.0)) << angle;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(grid.CastRay(origin, Eigen::Vector2d(nan, 0.0), 6.0), 6.0);
}

TEST(OccupancyGridTest, CastRayEdgeCases) {
  OccupancyGrid grid(0.1, {0.0, 0.0}, 10, 10);
  grid.SetCell(5, 5, CellState::kOccupied);
  grid.UpdateDistanceField();
  // Inside an occupied cell: zero.
  EXPECT_EQ(grid.CastRay({0.55, 0.55}, 1.0, 5.0), 0.0);
  // From far away, entering the grid.
  EXPECT_NEAR(grid.CastRay({-1e6, 0.55}, 0.0, 2e6), 1e6 + 0.5, 1e-6);
  EXPECT_EQ(grid.CastRay({-1e6, 0.55}, std::numbers::pi, 2e6), 2e6);
  // Degenerate arguments come back as max_range.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(grid.CastRay({nan, 0.5}, 0.0, 3.0), 3.0);
  EXPECT_EQ(grid.CastRay({0.05, 0.55}, kInfinity, 3.0), 3.0);
  EXPECT_EQ(grid.CastRay({0.05, 0.55}, 0.0, 0.0), 0.0);
  EXPECT_EQ(grid.CastRay({0.05, 0.55}, 0.0, -1.0), -1.0);
  EXPECT_TRUE(std::isnan(grid.CastRay({0.05, 0.55}, 0.0, nan)));
  EXPECT_EQ(grid.CastRay({0.05, 0.05}, 0.3, kInfinity), kInfinity);
}

TEST(OccupancyGridTest, MutationDropsDistanceFieldAndCastStaysCorrect) {
  OccupancyGrid grid(0.1, {0.0, 0.0}, 40, 10);
  grid.SetCell(30, 5, CellState::kOccupied);
  grid.UpdateDistanceField();
  EXPECT_NEAR(grid.CastRay({0.05, 0.55}, 0.0, 10.0), 2.95, 1e-9);
  grid.SetCell(10, 5, CellState::kOccupied);
  EXPECT_FALSE(grid.has_distance_field());
  EXPECT_NEAR(grid.CastRay({0.05, 0.55}, 0.0, 10.0), 0.95, 1e-9);
  grid.UpdateDistanceField();
  grid.InsertScan(MakeScan(0.0, 0.0, {0.5f}), Pose2(0.05, 0.15, 0.0));
  EXPECT_FALSE(grid.has_distance_field());
  EXPECT_NEAR(grid.CastRay({0.05, 0.15}, 0.0, 10.0), 0.45, 1e-9);
}

TEST(OccupancyGridTest, RoomScanCastsBackToItsRanges) {
  // A 6 x 4 m room scanned from one pose.
  const double x0 = -0.02, x1 = 6.02, y0 = -0.02, y1 = 4.02;
  const Pose2 pose(2.3, 1.7, 0.2);
  const int beams = 360;
  const double increment = 2.0 * std::numbers::pi / beams;
  std::vector<float> ranges;
  for (int i = 0; i < beams; ++i) {
    const double angle = pose.theta() - std::numbers::pi + i * increment;
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    double t = kInfinity;
    if (d.x() > 0) t = std::min(t, (x1 - pose.x()) / d.x());
    if (d.x() < 0) t = std::min(t, (x0 - pose.x()) / d.x());
    if (d.y() > 0) t = std::min(t, (y1 - pose.y()) / d.y());
    if (d.y() < 0) t = std::min(t, (y0 - pose.y()) / d.y());
    ranges.push_back(static_cast<float>(t));
  }
  const std::vector<LaserScan> scans{MakeScan(-std::numbers::pi, increment, ranges)};
  const std::vector<Pose2> poses{pose};
  const double res = 0.05;
  // The margin puts the walls mid-cell, away from cell boundaries where end points could fall
  // on either side.
  const OccupancyGrid grid = OccupancyGrid::FromScans(scans, poses, res, 6.5 * res);
  int close = 0;
  for (std::size_t i = 0; i < scans[0].size(); ++i) {
    const double cast = grid.CastRay(pose.translation(), pose.theta() + scans[0].angle(i), 10.0);
    // Every beam's end cell is occupied, so the ray stops there or earlier.
    EXPECT_LE(cast, scans[0].ranges[i] + 1e-5) << i;
    close += cast >= scans[0].ranges[i] - 2.0 * res;
  }
  // A ray that meets the wall at a slant can stop in a neighbouring beam's end cell a little
  // early; nearly all come back within two cells.
  EXPECT_GE(close, beams * 95 / 100);
}

}  // namespace
}  // namespace evoslam
