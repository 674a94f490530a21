#include "common/slam/immune/scan_gaps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>
#include <vector>

#include "common/line_map/line_map.h"
#include "common/sim/sim_testing.h"
#include "common/transform/angle_units.h"

namespace evoslam {
namespace {

constexpr double kGapTestMaxRange = 3.0;    // the method's cut (004 §4)
constexpr double kGapTestSensorMax = 80.0;  // what the laser reads where it sees nothing

// A 181-beam scan over 180 degrees, one beam a degree, with these ranges.
LaserScan GapTestScan(std::vector<float> ranges) {
  LaserScan scan;
  scan.angle_min = -90 * kDegree;
  scan.angle_increment = 1 * kDegree;
  scan.range_max = kGapTestSensorMax;
  scan.ranges = std::move(ranges);
  return scan;
}

// The scan a laser at `pose` takes of the walls of `map`.
LaserScan GapTestScanOf(const LineMap& map, const Pose2& pose) {
  LaserScan scan = GapTestScan(std::vector<float>(181));
  for (std::size_t i = 0; i < scan.size(); ++i) {
    scan.ranges[i] = static_cast<float>(
        map.CastRay(pose.translation(), pose.theta() + scan.angle(i), kGapTestSensorMax));
  }
  return scan;
}

// The ranges of `count` beams.
std::vector<float> GapTestBeams(std::size_t count, float range) {
  return std::vector<float>(count, range);
}

std::vector<float> GapTestRanges(std::initializer_list<std::vector<float>> parts) {
  std::vector<float> all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

Eigen::Vector2d GapTestPoint(const LaserScan& scan, std::size_t i) {
  return scan.ranges[i] * Eigen::Vector2d(std::cos(scan.angle(i)), std::sin(scan.angle(i)));
}

// A box whose near corner, at (1, 0.2), stands in front of a wall 2.5 m ahead. The box's front
// face runs out of range to the right, so its left end is its only edge within reach.
TEST(FindScanGapsTest, BoxCornerInFrontOfFarWallGivesOneGapAtTheCorner) {
  const Eigen::Vector2d corner(1.0, 0.2);
  const LineMap map({{{1.0, -6.0}, corner}, {corner, {1.4, 0.2}}, {{2.5, -3.0}, {2.5, 3.0}}});
  const LaserScan scan = GapTestScanOf(map, Pose2());
  const std::vector<ScanGap> gaps = FindScanGaps(scan, {}, kGapTestMaxRange);
  ASSERT_EQ(gaps.size(), 1u);
  const ScanGap& gap = gaps[0];
  const double spacing = corner.norm() * scan.angle_increment;
  EXPECT_LT((gap.point - corner).norm(), spacing);
  EXPECT_TRUE(gap.point.isApprox(GapTestPoint(scan, gap.beam)));
  // The gap reaches the wall, seen by the next beam past the corner.
  EXPECT_NEAR(gap.width_m, (GapTestPoint(scan, gap.beam + 1) - gap.point).norm(), 1e-6);
  EXPECT_LT(gap.point.norm(), GapTestPoint(scan, gap.beam + 1).norm());
}

// Seen from the other side, the near edge is the first beam of its section.
TEST(FindScanGapsTest, NearEdgeOnEitherSide) {
  const LaserScan left =
      GapTestScan(GapTestRanges({GapTestBeams(90, 2.5F), GapTestBeams(91, 1.0F)}));
  const std::vector<ScanGap> gaps = FindScanGaps(left, {}, kGapTestMaxRange);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].beam, 90u);
  const LaserScan right =
      GapTestScan(GapTestRanges({GapTestBeams(90, 1.0F), GapTestBeams(91, 2.5F)}));
  const std::vector<ScanGap> mirrored = FindScanGaps(right, {}, kGapTestMaxRange);
  ASSERT_EQ(mirrored.size(), 1u);
  EXPECT_EQ(mirrored[0].beam, 89u);
  EXPECT_NEAR(mirrored[0].width_m, gaps[0].width_m, 1e-9);
}

TEST(FindScanGapsTest, ContinuousWallsGiveNone) {
  const LineMap wall({{{1.5, -10.0}, {1.5, 10.0}}});
  EXPECT_TRUE(FindScanGaps(GapTestScanOf(wall, Pose2()), {}, kGapTestMaxRange).empty());
  // A room's corners are concave: its walls run on without a break.
  const LineMap room = testing::Room(4.0, 3.0);
  for (const double heading : {0.0, 1.0, 2.5, -2.0}) {
    EXPECT_TRUE(
        FindScanGaps(GapTestScanOf(room, Pose2(2.0, 1.5, heading)), {}, kGapTestMaxRange).empty());
  }
}

// A post 1 m ahead, 0.1 m wide, in front of a wall 2.5 m ahead: a section of 6 beams.
TEST(FindScanGapsTest, ShortSectionsAreDroppedAndMakeNoGap) {
  const LineMap map({{{1.0, -0.05}, {1.0, 0.05}},
                     {{1.0, 0.05}, {1.1, 0.05}},
                     {{1.0, -0.05}, {1.1, -0.05}},
                     {{2.5, -3.0}, {2.5, 3.0}}});
  const LaserScan scan = GapTestScanOf(map, Pose2());
  EXPECT_TRUE(FindScanGaps(scan, {}, kGapTestMaxRange).empty());
  proto::KeyPointParams short_ok;
  short_ok.set_min_section_points(3);
  const std::vector<ScanGap> gaps = FindScanGaps(scan, short_ok, kGapTestMaxRange);
  ASSERT_EQ(gaps.size(), 2u);  // both sides of the post
  EXPECT_NEAR(gaps[0].point.x(), 1.0, 1e-5);
  EXPECT_NEAR(gaps[1].point.x(), 1.0, 1e-5);
  EXPECT_LT(gaps[0].point.y(), gaps[1].point.y());
}

// Where a section ends at something nearer, its end is the far edge of that thing's shadow, not
// a corner: a leg of 3 beams in front of a box edge hides it.
TEST(FindScanGapsTest, AnEndHiddenByAnythingNearerIsNoNearEdge) {
  const LaserScan scan = GapTestScan(
      GapTestRanges({GapTestBeams(80, 2.0F), GapTestBeams(3, 0.5F), GapTestBeams(98, 2.9F)}));
  EXPECT_TRUE(FindScanGaps(scan, {}, kGapTestMaxRange).empty());
}

// A mixed reading between an edge and its background (a beam half on each), when eq. 6 parts it
// from both, is a dropped section that the gap spans.
TEST(FindScanGapsTest, GapSpansAMixedReading) {
  const LaserScan scan = GapTestScan(
      GapTestRanges({GapTestBeams(80, 1.0F), GapTestBeams(1, 1.6F), GapTestBeams(100, 2.5F)}));
  proto::KeyPointParams params;
  params.set_section_ratio(0.5);
  const std::vector<ScanGap> gaps = FindScanGaps(scan, params, kGapTestMaxRange);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].beam, 79u);
  EXPECT_NEAR(gaps[0].width_m, (GapTestPoint(scan, 81) - GapTestPoint(scan, 79)).norm(), 1e-6);
}

// An unreadable beam (at or below range_min, or NaN) leaves unknown what lies beyond the edge.
TEST(FindScanGapsTest, UnknownReadingsBreakSectionsWithoutAGap) {
  for (const float unknown : {0.0F, std::numeric_limits<float>::quiet_NaN()}) {
    const LaserScan scan = GapTestScan(
        GapTestRanges({GapTestBeams(80, 1.0F), GapTestBeams(1, unknown), GapTestBeams(100, 2.5F)}));
    EXPECT_TRUE(FindScanGaps(scan, {}, kGapTestMaxRange).empty());
  }
}

// Beyond max range stands for a surface at max range: an edge at 1 m against open space counts,
// as wide as the gap to max range at least; a wall that runs out of range at 2.9 m does not.
TEST(FindScanGapsTest, EdgesAgainstOpenSpace) {
  for (const float open :
       {static_cast<float>(kGapTestSensorMax), 5.0F, std::numeric_limits<float>::infinity()}) {
    const LaserScan scan =
        GapTestScan(GapTestRanges({GapTestBeams(80, 1.0F), GapTestBeams(101, open)}));
    const std::vector<ScanGap> gaps = FindScanGaps(scan, {}, kGapTestMaxRange);
    ASSERT_EQ(gaps.size(), 1u) << open;
    EXPECT_EQ(gaps[0].beam, 79u);
    const Eigen::Vector2d at_max_range =
        kGapTestMaxRange * Eigen::Vector2d(std::cos(scan.angle(80)), std::sin(scan.angle(80)));
    EXPECT_NEAR(gaps[0].width_m, (at_max_range - gaps[0].point).norm(), 1e-6);
  }
  const LaserScan fading =
      GapTestScan(GapTestRanges({GapTestBeams(80, 2.9F), GapTestBeams(101, kGapTestSensorMax)}));
  EXPECT_TRUE(FindScanGaps(fading, {}, kGapTestMaxRange).empty());
  // The same edge within a longer cut is a gap.
  EXPECT_EQ(FindScanGaps(fading, {}, 6.0).size(), 1u);
}

// Eq. 6 splits two neighbouring points when their distance reaches section_ratio times the
// nearer range.
TEST(FindScanGapsTest, SectionRatioDecidesTheBreak) {
  const LaserScan scan =
      GapTestScan(GapTestRanges({GapTestBeams(90, 1.0F), GapTestBeams(91, 2.0F)}));
  const double ratio = (GapTestPoint(scan, 90) - GapTestPoint(scan, 89)).norm() / 1.0;
  proto::KeyPointParams params;
  params.set_section_ratio(ratio * 1.01);
  EXPECT_TRUE(FindScanGaps(scan, params, kGapTestMaxRange).empty());
  params.set_section_ratio(ratio * 0.99);
  EXPECT_EQ(FindScanGaps(scan, params, kGapTestMaxRange).size(), 1u);
}

TEST(FindScanGapsTest, GapsNoWiderThanMinGapCountNot) {
  const LaserScan scan =
      GapTestScan(GapTestRanges({GapTestBeams(90, 1.0F), GapTestBeams(91, 1.3F)}));
  const double width = (GapTestPoint(scan, 90) - GapTestPoint(scan, 89)).norm();
  proto::KeyPointParams params;
  params.set_section_ratio(0.1);  // so that the two are sections
  params.set_min_gap_m(width * 1.01);
  EXPECT_TRUE(FindScanGaps(scan, params, kGapTestMaxRange).empty());
  params.set_min_gap_m(width * 0.99);
  const std::vector<ScanGap> gaps = FindScanGaps(scan, params, kGapTestMaxRange);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_NEAR(gaps[0].width_m, width, 1e-9);
}

TEST(FindScanGapsTest, EmptyScanHasNone) {
  EXPECT_TRUE(FindScanGaps(GapTestScan({}), {}, kGapTestMaxRange).empty());
}

}  // namespace
}  // namespace evoslam
