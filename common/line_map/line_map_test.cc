#include "common/line_map/line_map.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "common/io/testing_files.h"
#include "common/line_map/segment_geometry.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using std::numbers::pi;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kMax = 100.0;

LineMap Box(double x0, double y0, double x1, double y1, double cell_size = 0.5) {
  return LineMap(
      {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}},
      cell_size);
}

// Tests every wall. The intersection arithmetic is written the same way as in the index so that
// the comparison checks which walls the index visits rather than rounding at wall ends.
double BruteForceCast(std::span<const Segment> walls, const Eigen::Vector2d& o, double angle,
                      double max_range) {
  const double dx = std::cos(angle);
  const double dy = std::sin(angle);
  double best = max_range;
  for (const Segment& w : walls) {
    const double ex = w.b.x() - w.a.x();
    const double ey = w.b.y() - w.a.y();
    const double wx = w.a.x() - o.x();
    const double wy = w.a.y() - o.y();
    const double sign = dx * ey - dy * ex < 0.0 ? -1.0 : 1.0;
    const double den = sign * (dx * ey - dy * ex);
    const double t_num = sign * (wx * ey - wy * ex);
    const double s_num = sign * (wx * dy - wy * dx);
    if (den <= 1e-12 * (std::abs(ex) + std::abs(ey))) continue;
    if (t_num >= 0.0 && s_num >= 0.0 && s_num <= den && t_num < best * den) best = t_num / den;
  }
  return std::min(best, max_range);
}

std::vector<Segment> RandomWalls(std::mt19937_64& gen, int count, double size, double max_len) {
  std::uniform_real_distribution<double> pos(0.0, size);
  std::uniform_real_distribution<double> len(0.05, max_len);
  std::uniform_real_distribution<double> ang(-pi, pi);
  std::vector<Segment> walls;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d a(pos(gen), pos(gen));
    const double l = len(gen);
    const double t = ang(gen);
    walls.push_back({a, a + l * Eigen::Vector2d(std::cos(t), std::sin(t))});
  }
  return walls;
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

TEST(LineMapTest, EmptyMapReturnsMaxRange) {
  const LineMap map;
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.CastRay({0, 0}, 0.3, 7.5), 7.5);
  EXPECT_TRUE(map.SegmentsNear({0, 0}, 10.0).empty());
  const LineMap also_empty(std::vector<Segment>{});
  EXPECT_EQ(also_empty.CastRay({1, 2}, -1.0, 3.0), 3.0);
}

TEST(LineMapTest, BoundsCoverAllWalls) {
  const LineMap map({{{1, 5}, {-2, 3}}, {{4, -1}, {0, 0}}});
  EXPECT_EQ(map.bounds().min, Eigen::Vector2d(-2, -1));
  EXPECT_EQ(map.bounds().max, Eigen::Vector2d(4, 5));
  EXPECT_EQ(map.size(), 2u);
}

TEST(LineMapTest, AxisAlignedWalls) {
  const LineMap map = Box(0, 0, 4, 3);
  EXPECT_NEAR(map.CastRay({1, 1}, 0.0, kMax), 3.0, 1e-12);
  EXPECT_NEAR(map.CastRay({1, 1}, pi / 2, kMax), 2.0, 1e-12);
  EXPECT_NEAR(map.CastRay({1, 1}, pi, kMax), 1.0, 1e-12);
  EXPECT_NEAR(map.CastRay({1, 1}, -pi / 2, kMax), 1.0, 1e-12);
  // 30 degrees up: meets the right wall x = 4 at y = 1 + 3 tan 30 < 3.
  EXPECT_NEAR(map.CastRay({1, 1}, pi / 6, kMax), 3.0 / std::cos(pi / 6), 1e-12);
}

TEST(LineMapTest, DiagonalWall) {
  // The line x + y = 2 between (2, 0) and (0, 2).
  const LineMap map({{{2, 0}, {0, 2}}});
  EXPECT_NEAR(map.CastRay({0, 0}, pi / 4, kMax), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(map.CastRay({0, 0}, 0.0, kMax), 2.0, 1e-12);  // the wall's end point
  EXPECT_EQ(map.CastRay({0, 0}, -0.1, kMax), kMax);         // passes below the wall's end
  EXPECT_EQ(map.CastRay({0, 0}, pi + pi / 4, kMax), kMax);  // pointing away
  // From the far side, through the wall.
  EXPECT_NEAR(map.CastRay({3, 3}, -3 * pi / 4, kMax), 2.0 * std::sqrt(2.0), 1e-12);
}

TEST(LineMapTest, RayIntoCorner) {
  const LineMap map = Box(0, 0, 4, 3);
  const double angle = std::atan2(2.0, 3.0);  // from (1, 1) straight at the corner (4, 3)
  EXPECT_NEAR(map.CastRay({1, 1}, angle, kMax), std::sqrt(13.0), 1e-12);
}

TEST(LineMapTest, RayFromOutsideTheBounds) {
  const LineMap map = Box(0, 0, 4, 3);
  EXPECT_NEAR(map.CastRay({-3, 1.5}, 0.0, kMax), 3.0, 1e-12);
  EXPECT_NEAR(map.CastRay({8, 1.5}, pi, kMax), 4.0, 1e-12);
  EXPECT_NEAR(map.CastRay({2, -10}, pi / 2, kMax), 10.0, 1e-12);
  // Diagonally from far away at the corner region: hits the bottom wall at (1, 0).
  EXPECT_NEAR(map.CastRay({-9, -10}, pi / 4, kMax), 10.0 * std::sqrt(2.0), 1e-12);
  EXPECT_EQ(map.CastRay({-3, 5}, 0.0, kMax), kMax);   // passes above the map
  EXPECT_EQ(map.CastRay({-3, 1.5}, pi, kMax), kMax);  // points away from the map
  EXPECT_EQ(map.CastRay({-3, 1.5}, 0.0, 2.5), 2.5);   // map lies beyond max range
}

TEST(LineMapTest, ParallelRays) {
  const LineMap wall({{{0, 0}, {4, 0}}});
  EXPECT_EQ(wall.CastRay({-1, 0.5}, 0.0, kMax), kMax);
  EXPECT_EQ(wall.CastRay({-1, -0.5}, pi, kMax), kMax);
  // A ray running along a wall of a room still meets the wall across its path.
  const LineMap room = Box(0, 0, 4, 3);
  EXPECT_NEAR(room.CastRay({1, 0}, 0.0, kMax), 3.0, 1e-12);
  EXPECT_NEAR(room.CastRay({1, 3}, 0.0, kMax), 3.0, 1e-12);
}

TEST(LineMapTest, MaxRange) {
  const LineMap map({{{5, -1}, {5, 1}}});
  EXPECT_EQ(map.CastRay({0, 0}, 0.0, 3.0), 3.0);
  EXPECT_NEAR(map.CastRay({0, 0}, 0.0, 5.5), 5.0, 1e-12);
  EXPECT_EQ(map.CastRay({0, 0}, 0.0, 0.0), 0.0);
}

TEST(LineMapTest, OriginOnWallReadsZero) {
  const LineMap map = Box(0, 0, 4, 3);
  EXPECT_EQ(map.CastRay({0, 1}, 0.0, kMax), 0.0);
}

TEST(LineMapTest, AgreesWithBruteForceOnRandomMaps) {
  std::mt19937_64 gen(42);
  for (const double cell_size : {0.25, 0.5, 1.3, 50.0}) {
    const std::vector<Segment> walls = RandomWalls(gen, 200, 20.0, 3.0);
    const LineMap map(walls, cell_size);
    std::uniform_real_distribution<double> pos(-8.0, 28.0);
    std::uniform_real_distribution<double> ang(-pi, pi);
    std::uniform_real_distribution<double> range(0.1, 40.0);
    for (int i = 0; i < 5000; ++i) {
      const Eigen::Vector2d o(pos(gen), pos(gen));
      const double a = ang(gen);
      const double r = range(gen);
      ASSERT_NEAR(map.CastRay(o, a, r), BruteForceCast(walls, o, a, r), 1e-9)
          << "cell " << cell_size << " origin " << o.transpose() << " angle " << a << " range "
          << r;
    }
  }
}

TEST(LineMapTest, DirectionCastEqualsAngleCast) {
  std::mt19937_64 gen(5);
  const LineMap map(RandomWalls(gen, 100, 20.0, 3.0));
  std::uniform_real_distribution<double> pos(0.0, 20.0);
  std::uniform_real_distribution<double> ang(-pi, pi);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector2d o(pos(gen), pos(gen));
    const double a = ang(gen);
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    ASSERT_EQ(map.CastRay(o, d, 15.0), map.CastRay(o, a, 15.0)) << o.transpose() << " " << a;
  }
}

TEST(LineMapTest, AgreesWithBruteForceAlongCellBorders) {
  // Walls and rays on the index's cell borders, where hits fall exactly between cells.
  std::mt19937_64 gen(7);
  std::uniform_int_distribution<int> coord(0, 16);
  std::vector<Segment> walls;
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector2d a(coord(gen) * 0.5, coord(gen) * 0.5);
    Eigen::Vector2d b(coord(gen) * 0.5, coord(gen) * 0.5);
    if (a == b) b.x() += 0.5;
    walls.push_back({a, b});
  }
  const LineMap map(walls, 0.5);
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector2d o(coord(gen) * 0.5 - 0.5, coord(gen) * 0.5 - 0.5);
    const double a = (i % 8) * pi / 4;
    ASSERT_NEAR(map.CastRay(o, a, 30.0), BruteForceCast(walls, o, a, 30.0), 1e-9)
        << "origin " << o.transpose() << " angle " << a;
  }
}

TEST(LineMapTest, CoarsensIndexForHugeMaps) {
  const std::vector<Segment> walls = {{{0, 0}, {1e5, 0}}, {{1e5, 0}, {1e5, 1e5}}};
  const LineMap map(walls, 0.01);
  EXPECT_NEAR(map.CastRay({5e4, 10}, -pi / 2, 1e6), 10.0, 1e-6);
  EXPECT_NEAR(map.CastRay({5e4, 10}, 0.0, 1e6), 5e4, 1e-6);
}

TEST(LineMapTest, RejectsBadConstruction) {
  const double nan = std::nan("");
  EXPECT_THROW(LineMap({{{0, 0}, {nan, 1}}}), Error);
  EXPECT_THROW(LineMap({{{0, 0}, {1, 1}}}, 0.0), Error);
  EXPECT_THROW(LineMap({{{0, 0}, {1, 1}}}, -1.0), Error);
}

TEST(LineMapTest, SegmentsNearUsesExactDistance) {
  const LineMap map({{{-1, 1}, {1, 1}},              // 0: distance 1 from the origin
                     {{1, 0}, {2, 0}},               // 1: distance 1 (its end point)
                     {{2, 2}, {3, 3}},               // 2: distance sqrt(8)
                     {{-0.5, -0.5}, {0.5, -0.5}}});  // 3: distance 0.5
  EXPECT_THAT(map.SegmentsNear({0, 0}, 1.0), ElementsAre(0, 1, 3));
  EXPECT_THAT(map.SegmentsNear({0, 0}, 0.999), ElementsAre(3));
  EXPECT_THAT(map.SegmentsNear({0, 0}, 0.4), ElementsAre());
  EXPECT_THAT(map.SegmentsNear({0, 0}, 3.0), ElementsAre(0, 1, 2, 3));
  EXPECT_THAT(map.SegmentsNear({50, 50}, 1.0), ElementsAre());
  EXPECT_THAT(map.SegmentsNear({0, 0}, -1.0), ElementsAre());
}

TEST(LineMapTest, SegmentsNearAgreesWithBruteForce) {
  std::mt19937_64 gen(3);
  const std::vector<Segment> walls = RandomWalls(gen, 300, 20.0, 4.0);
  const LineMap map(walls, 0.5);
  std::uniform_real_distribution<double> pos(-5.0, 25.0);
  std::uniform_real_distribution<double> radius(0.0, 4.0);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d c(pos(gen), pos(gen));
    const double r = radius(gen);
    std::vector<std::size_t> expected;
    for (std::size_t k = 0; k < walls.size(); ++k) {
      if (PointSegmentDistance(c, walls[k]) <= r) expected.push_back(k);
    }
    ASSERT_EQ(map.SegmentsNear(c, r), expected) << "centre " << c.transpose() << " radius " << r;
  }
}

TEST(LineMapIoTest, RoundTripIsExact) {
  std::mt19937_64 gen(11);
  const std::vector<Segment> walls = RandomWalls(gen, 50, 30.0, 5.0);
  const TempDir dir;
  const std::filesystem::path path = dir / "roundtrip.lines";
  WriteLineMap(LineMap(walls), path);
  const LineMap read = ReadLineMap(path);
  ASSERT_EQ(read.size(), walls.size());
  for (std::size_t i = 0; i < walls.size(); ++i) {
    EXPECT_EQ(read.segments()[i].a, walls[i].a);
    EXPECT_EQ(read.segments()[i].b, walls[i].b);
  }
}

TEST(LineMapIoTest, SkipsCommentsAndBlankLines) {
  const TempDir dir;
  const std::filesystem::path path = dir / "comments.lines";
  WriteText(path, "# a room\n\n  0 0 4 0   # floor\n\t\n4 0 +4 3.5\r\n-1e-1 2 3 2\n");
  const LineMap map = ReadLineMap(path);
  ASSERT_EQ(map.size(), 3u);
  EXPECT_EQ(map.segments()[1].b, Eigen::Vector2d(4, 3.5));
  EXPECT_EQ(map.segments()[2].a, Eigen::Vector2d(-0.1, 2));
}

// A world drawn elsewhere often comes compressed; it reads as the plain file does, and an error
// in it still names the line.
TEST(LineMapIoTest, ReadsGzipAndBzip2AsThePlainFile) {
  const std::string text = "# a room\n0 0 4 0\n4 0 4 3.5\n4 3.5 0 3.5\n";
  const TempDir dir;
  io_testing::WriteBytes(dir / "room.lines.gz", io_testing::GzipBytes(text));
  io_testing::WriteBytes(dir / "room.lines.bz2", io_testing::Bzip2Bytes(text));
  WriteText(dir / "room.lines", text);
  const LineMap plain = ReadLineMap(dir / "room.lines");
  ASSERT_EQ(plain.size(), 3u);
  for (const char* name : {"room.lines.gz", "room.lines.bz2"}) {
    const LineMap read = ReadLineMap(dir / name);
    ASSERT_EQ(read.size(), plain.size()) << name;
    for (std::size_t i = 0; i < plain.size(); ++i) {
      EXPECT_EQ(read.segments()[i].a, plain.segments()[i].a) << name;
      EXPECT_EQ(read.segments()[i].b, plain.segments()[i].b) << name;
    }
  }
  const std::filesystem::path bad = dir / "bad.lines.gz";
  io_testing::WriteBytes(bad, io_testing::GzipBytes("0 0 4 0\n0 0 4\n"));
  try {
    ReadLineMap(bad);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(bad.string() + ":2: expected a wall as 4 numbers"));
  }
}

TEST(LineMapIoTest, MalformedLinesNameFileAndLine) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"0 0 1 1\n\n0 0 1\n", ":3: expected a wall as 4 numbers"},
      {"0 0 1 1 5\n", ":1: expected a wall as 4 numbers"},
      {"# c\n0 0 one 1\n", ":2: expected a finite number for field 3"},
      {"0 nan 1 1\n", ":1: expected a finite number for field 2"},
      {"0 0 1 inf\n", ":1: expected a finite number"},
      {"0 0 1 1x\n", ":1: expected a finite number for field 4"},
      {"1 2 1 2\n", ":1: expected a wall of non-zero length"},
  };
  const TempDir dir;
  int i = 0;
  for (const auto& c : cases) {
    const std::filesystem::path path = dir / ("bad" + std::to_string(i++) + ".lines");
    WriteText(path, c.text);
    try {
      ReadLineMap(path);
      ADD_FAILURE() << "no error for " << c.text;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string() + c.expected)) << c.text;
    }
  }
}

TEST(LineMapIoTest, MissingFileNamesPath) {
  const TempDir dir;
  const std::filesystem::path path = dir / "does_not_exist.lines";
  try {
    ReadLineMap(path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
  try {
    ReadLineMap(dir.path());
    ADD_FAILURE() << "no error for a directory";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(dir.path().string() + ": cannot read"));
  }
  EXPECT_THROW(WriteLineMap(LineMap(), dir / "no_such_dir" / "x.lines"), Error);
}

}  // namespace
}  // namespace evoslam
