#include "common/slam/rss/scan_refinement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "common/line_map/line_map.h"
#include "common/localization/test_scenes.h"
#include "common/sensor/laser_scan.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// 5 cm cells from (-1, -1); BoxRoom spans x in [0, 6], y in [0, 8].
HitCountGrid RoomMap() {
  HitCountGrid map(0.05, Eigen::Vector2d(-1.0, -1.0), 180, 200);
  const LineMap room = testing::BoxRoom();
  for (int i = 0; i < 8; ++i) {
    const Pose2 pose(2.2 + 0.15 * i, 1.8 + 0.2 * i, 0.3 + 0.15 * i);
    map.AddScan(testing::ScanFrom(room, pose), pose);
  }
  return map;
}

// The returns of a scan of the room of RoomMap taken at `pose`.
std::vector<Eigen::Vector2d> RoomReturns(const Pose2& pose) {
  return ReturnPoints(testing::ScanFrom(testing::BoxRoom(), pose));
}

// Two long parallel walls, each at the centre of a row of 5 cm cells, and a map of them in which
// each wall fills its row once.
constexpr double kCorridorWall = 1.025;
LineMap CorridorWalls() {
  return LineMap(std::vector<Segment>{{{-20.0, -kCorridorWall}, {20.0, -kCorridorWall}},
                                      {{-20.0, kCorridorWall}, {20.0, kCorridorWall}}});
}
HitCountGrid CorridorMap() {
  HitCountGrid map(0.05, Eigen::Vector2d(-5.0, -3.0), 200, 120);
  for (int x = 0; x < map.width(); ++x) {
    for (const double y : {-kCorridorWall, kCorridorWall}) {
      map.Add(Eigen::Vector2d(-4.975 + 0.05 * x, y));
    }
  }
  return map;
}

double Distance(const Pose2& a, const Pose2& b) {
  return (a.translation() - b.translation()).norm();
}

TEST(SampleOccupancyTest, InterpolatesBetweenCellCentresOfABinaryOccupancy) {
  HitCountGrid map(0.1, Eigen::Vector2d(0.0, 0.0), 10, 10);
  map.Add(Eigen::Vector2d(0.55, 0.55));  // cell (5, 5), centred at (0.55, 0.55)
  const auto centre = SampleOccupancy(map, Eigen::Vector2d(0.55, 0.55), 0.0);
  ASSERT_TRUE(centre);
  EXPECT_DOUBLE_EQ(centre->value, 1.0);
  // A quarter of a cell to the right and half a cell up: 0.75 * 0.5 of the occupied corner.
  const auto off = SampleOccupancy(map, Eigen::Vector2d(0.575, 0.6), 0.0);
  ASSERT_TRUE(off);
  EXPECT_NEAR(off->value, 0.375, 1e-12);
  EXPECT_NEAR(off->gradient.x(), -0.5 / 0.1, 1e-9);   // falls to the right
  EXPECT_NEAR(off->gradient.y(), -0.75 / 0.1, 1e-9);  // and upwards
  const auto empty = SampleOccupancy(map, Eigen::Vector2d(0.2, 0.2), 0.0);
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->value, 0.0);
  EXPECT_EQ(empty->gradient, Eigen::Vector2d::Zero());
  // The four cells around the point must lie in the grid.
  EXPECT_FALSE(SampleOccupancy(map, Eigen::Vector2d(0.02, 0.5), 0.0));
  EXPECT_FALSE(SampleOccupancy(map, Eigen::Vector2d(0.5, 0.97), 0.0));
  EXPECT_FALSE(SampleOccupancy(map, Eigen::Vector2d(std::nan(""), 0.5), 0.0));
}

// Counts across a wall along x, in the cells x = 3 to 6 of rows 4 to 6: row 5 holds the wall,
// rows 4 and 6 the few hits range noise scattered, and along the wall the counts vary.
HitCountGrid NoisyWall() {
  HitCountGrid map(0.1, Eigen::Vector2d(0.0, 0.0), 10, 10);
  for (int x = 3; x <= 6; ++x) {
    const Eigen::Vector2d centre(0.05 + 0.1 * x, 0.55);
    map.Add(centre, x == 4 ? 12 : 20);
    map.Add(centre + Eigen::Vector2d(0.0, -0.1), 2);
    map.Add(centre + Eigen::Vector2d(0.0, 0.1), 3);
  }
  return map;
}

TEST(SampleOccupancyTest, ReadAgainstTheStrongestCountNearbyAWallPeaksAlongItsMiddle) {
  const HitCountGrid map = NoisyWall();
  // With a share of 0.3 the wall's cells (12 and 20 against 20) read 1, the noise either side
  // 2 / 6 and 3 / 6 of that.
  const auto wall = SampleOccupancy(map, Eigen::Vector2d(0.45, 0.55), 0.3);
  ASSERT_TRUE(wall);
  EXPECT_DOUBLE_EQ(wall->value, 1.0);
  EXPECT_NEAR(wall->gradient.x(), 0.0, 1e-9);  // level along the wall, though its counts vary
  const auto below = SampleOccupancy(map, Eigen::Vector2d(0.45, 0.50), 0.3);
  ASSERT_TRUE(below);
  EXPECT_NEAR(below->value, 0.5 * (1.0 + 2.0 / 6.0), 1e-12);
  EXPECT_NEAR(below->gradient.y(), (1.0 - 2.0 / 6.0) / 0.1, 1e-9);  // rises towards the wall
  const auto above = SampleOccupancy(map, Eigen::Vector2d(0.45, 0.60), 0.3);
  ASSERT_TRUE(above);
  EXPECT_NEAR(above->gradient.y(), (3.0 / 6.0 - 1.0) / 0.1, 1e-9);  // falls away from it
  // Read as binary, the three rows are one flat plateau.
  const auto flat = SampleOccupancy(map, Eigen::Vector2d(0.45, 0.50), 0.0);
  ASSERT_TRUE(flat);
  EXPECT_DOUBLE_EQ(flat->value, 1.0);
  EXPECT_EQ(flat->gradient, Eigen::Vector2d::Zero());
  // A share of 1 reads the counts themselves against the strongest, along the wall too.
  const auto raw = SampleOccupancy(map, Eigen::Vector2d(0.45, 0.55), 1.0);
  ASSERT_TRUE(raw);
  EXPECT_NEAR(raw->value, 12.0 / 20.0, 1e-12);
  EXPECT_NEAR(raw->gradient.x(), (20.0 - 12.0) / 20.0 / 0.1, 1e-9);
}

TEST(RefineScanPoseTest, MovesAPoseOffByLessThanACellTowardsTheTruth) {
  const HitCountGrid map = RoomMap();
  const Pose2 truth(3.1, 2.5, 0.8);
  const std::vector<Eigen::Vector2d> returns = RoomReturns(truth);
  ScanRefinementParams params;
  params.set_iterations(10);
  for (const Pose2& off :
       {Pose2(0.03, -0.02, 0.0), Pose2(-0.025, 0.0, 0.01), Pose2(0.0, 0.035, -0.012)}) {
    const Pose2 start = truth * off;
    const Pose2 refined = RefineScanPose(map, returns, start, params).pose;
    EXPECT_LT(Distance(refined, truth), 0.5 * Distance(start, truth)) << off;
    EXPECT_LT(std::abs(refined.theta() - truth.theta()),
              std::max(0.003, 0.5 * std::abs(start.theta() - truth.theta())))
        << off;
  }
}

// The constraint rule reads the refinement's information rather than summing it again: it must be
// the information at the pose returned, whether the refinement moved or stayed.
TEST(RefineScanPoseTest, HandsOnTheInformationAtThePoseItReturns) {
  const HitCountGrid map = RoomMap();
  const Pose2 truth(3.1, 2.5, 0.8);
  const std::vector<Eigen::Vector2d> returns = RoomReturns(truth);
  ScanRefinementParams params;
  for (const Pose2& start : {truth * Pose2(0.03, -0.02, 0.01), truth}) {
    for (const std::size_t iterations : {std::size_t{0}, std::size_t{1}, std::size_t{10}}) {
      params.set_iterations(iterations);
      const RefinedPose refined = RefineScanPose(map, returns, start, params);
      const Eigen::Matrix3d expected = ScanInformation(map, returns, refined.pose, 0.3);
      EXPECT_GT(expected.trace(), 0.0);
      EXPECT_EQ(refined.information, expected) << start << " after " << iterations;
    }
  }
  EXPECT_EQ(RefineScanPose(map, {}, truth, params).information, Eigen::Matrix3d::Zero());
}

TEST(RefineScanPoseTest, StaysWithinItsLimitsAndLeavesAPoseWithNothingToAlignTo) {
  const HitCountGrid map = RoomMap();
  const Pose2 truth(3.1, 2.5, 0.8);
  const std::vector<Eigen::Vector2d> returns = RoomReturns(truth);
  const Pose2 start = truth * Pose2(0.04, -0.03, 0.02);
  ScanRefinementParams params;
  params.set_iterations(10);
  params.set_max_shift_cells(0.2);  // 1 cm
  params.set_max_turn_rad(0.004);
  const Pose2 refined = RefineScanPose(map, returns, start, params).pose;
  EXPECT_LE(Distance(refined, start), 0.01 + 1e-12);
  EXPECT_LE(std::abs(refined.theta() - start.theta()), 0.004 + 1e-12);
  EXPECT_LT(Distance(refined, truth), Distance(start, truth));

  params.set_iterations(0);
  EXPECT_EQ(RefineScanPose(map, returns, start, params).pose, start);
  params.set_iterations(10);
  const HitCountGrid blank(0.05, Eigen::Vector2d(-1.0, -1.0), 180, 200);
  EXPECT_EQ(RefineScanPose(blank, returns, start, params).pose, start);
  EXPECT_EQ(RefineScanPose(map, {}, start, params).pose, start);
}

TEST(RefineScanPoseTest, AHeadingNearPiDoesNotWrapIntoTheLimit) {
  // Poses facing along -x, so that the headings straddle the wrap at pi.
  HitCountGrid map(0.05, Eigen::Vector2d(-1.0, -1.0), 180, 200);
  const LineMap room = testing::BoxRoom();
  const Pose2 truth(3.1, 4.0, std::numbers::pi - 0.001);
  for (int i = 0; i < 6; ++i) {
    const Pose2 pose(2.6 + 0.2 * i, 3.0 + 0.2 * i, std::numbers::pi - 0.3 + 0.1 * i);
    map.AddScan(testing::ScanFrom(room, pose), pose);
  }
  const std::vector<Eigen::Vector2d> returns = ReturnPoints(testing::ScanFrom(room, truth));
  const Pose2 start = truth * Pose2(0.02, 0.02, 0.008);  // heading past pi, wrapped to -pi + ...
  ScanRefinementParams params;
  params.set_iterations(10);
  const Pose2 refined = RefineScanPose(map, returns, start, params).pose;
  EXPECT_LT(Distance(refined, truth), Distance(start, truth));
  EXPECT_LT(std::abs(WrapAngle(refined.theta() - truth.theta())), 0.005);
}

// The corridor and a laser too short to see an end: the scan fixes the pose across the corridor
// and its heading, and nothing along it.
TEST(RefineScanPoseTest, AlongACorridorThePoseKeepsItsPlace) {
  const LineMap corridor = CorridorWalls();
  const HitCountGrid map = CorridorMap();
  const Pose2 truth(0.3, 0.0, 0.0);
  const std::vector<Eigen::Vector2d> returns =
      ReturnPoints(testing::ScanFrom(corridor, truth, 181, 4.0));
  const Pose2 start(0.32, 0.02, 0.005);
  const Pose2 refined = RefineScanPose(map, returns, start, ScanRefinementParams{}).pose;
  EXPECT_LT(std::abs(refined.y() - truth.y()), 0.5 * std::abs(start.y() - truth.y()));
  EXPECT_LT(std::abs(refined.theta() - truth.theta()), 0.5 * std::abs(start.theta()));
  EXPECT_NEAR(refined.x(), start.x(), 1e-9);
}

// The corridor's walls as range noise leaves them: a row of cells counted often with a row either
// side counted rarely. Read as binary, a wall is three cells thick and flat across, and a pose
// off by 2 cm across the corridor has nothing to follow; against the strongest count, each wall
// peaks along its middle and the refinement finds it.
TEST(RefineScanPoseTest, AcrossAThickWallThePoseFollowsTheCountsToItsMiddle) {
  const LineMap corridor = CorridorWalls();
  HitCountGrid map(0.05, Eigen::Vector2d(-5.0, -3.0), 200, 120);
  for (int x = 0; x < map.width(); ++x) {
    for (const double y : {-kCorridorWall, kCorridorWall}) {
      const Eigen::Vector2d centre(-4.975 + 0.05 * x, y);
      map.Add(centre, 10);
      map.Add(centre + Eigen::Vector2d(0.0, 0.05), 1);
      map.Add(centre - Eigen::Vector2d(0.0, 0.05), 1);
    }
  }
  const Pose2 truth(0.3, 0.0, 0.0);
  const std::vector<Eigen::Vector2d> returns =
      ReturnPoints(testing::ScanFrom(corridor, truth, 181, 4.0));
  const Pose2 start(0.3, 0.02, 0.0);
  ScanRefinementParams params;
  const Pose2 refined = RefineScanPose(map, returns, start, params).pose;
  EXPECT_LT(std::abs(refined.y() - truth.y()), 0.002) << refined;
  params.set_wall_share(0.0);
  EXPECT_EQ(RefineScanPose(map, returns, start, params).pose, start);
}

// The corridor of AlongACorridorThePoseKeepsItsPlace: a pose off its prior both ways keeps the
// offset across the corridor and in heading, which the scan measures, and takes the prior's
// place along it, which the scan cannot measure.
TEST(KeepPriorWhereUnconstrainedTest, AlongACorridorThePriorsPlaceIsTaken) {
  const LineMap corridor = CorridorWalls();
  const HitCountGrid map = CorridorMap();
  const Pose2 pose(0.45, 0.02, 0.004);
  const Pose2 prior(0.3, 0.0, 0.0);
  const std::vector<Eigen::Vector2d> returns =
      ReturnPoints(testing::ScanFrom(corridor, pose, 181, 4.0));
  const Pose2 kept = KeepPriorWhereUnconstrained(ScanInformation(map, returns, pose, 0.3), returns,
                                                 pose, prior, 0.005);
  EXPECT_NEAR(kept.x(), prior.x(), 1e-6) << kept;
  EXPECT_NEAR(kept.y(), pose.y(), 1e-6) << kept;
  EXPECT_NEAR(kept.theta(), pose.theta(), 1e-6) << kept;
  EXPECT_EQ(KeepPriorWhereUnconstrained(ScanInformation(map, returns, pose, 0.3), returns, pose,
                                        prior, 0.0),
            pose);
  EXPECT_EQ(
      KeepPriorWhereUnconstrained(ScanInformation(map, {}, pose, 0.3), {}, pose, prior, 0.005),
      pose);
}

// In a room every direction is pinned down: the pose stays. On a map with nothing on it, no
// direction is: the prior is taken.
TEST(KeepPriorWhereUnconstrainedTest, InARoomThePoseStaysOnABlankMapThePriorIsTaken) {
  const HitCountGrid map = RoomMap();
  const Pose2 pose(3.1, 2.5, 0.8);
  const Pose2 prior = pose * Pose2(0.1, -0.05, 0.03);
  const std::vector<Eigen::Vector2d> returns = RoomReturns(pose);
  const Pose2 kept = KeepPriorWhereUnconstrained(ScanInformation(map, returns, pose, 0.3), returns,
                                                 pose, prior, 0.005);
  EXPECT_NEAR(kept.x(), pose.x(), 1e-9);
  EXPECT_NEAR(kept.y(), pose.y(), 1e-9);
  EXPECT_NEAR(kept.theta(), pose.theta(), 1e-9);
  const HitCountGrid blank(0.05, Eigen::Vector2d(-1.0, -1.0), 180, 200);
  EXPECT_EQ(KeepPriorWhereUnconstrained(ScanInformation(blank, returns, pose, 0.3), returns, pose,
                                        prior, 0.005),
            prior);
}

// Returns 2 m out make a heading offset of 1 rad weigh as 2 m, so this information is 1 across
// x and the heading and 0.25 along y: shares 1, 0.25 and 1 of the best. A prior weighing half
// the best direction's information keeps 1 / 1.5 of the offset along x and the heading and
// 0.25 / 0.75 along y; y's share below the minimum ratio takes the prior's y.
TEST(KeepPriorWhereUnconstrainedTest, APriorWeightKeepsEachDirectionsShareOfTheOffset) {
  const std::vector<Eigen::Vector2d> returns = {{2.0, 0.0}, {0.0, 2.0}, {-2.0, 0.0}};
  const Eigen::Matrix3d information = Eigen::Vector3d(1.0, 0.25, 4.0).asDiagonal();
  const Pose2 prior(1.0, 2.0, 0.5);
  const Pose2 pose(1.1, 1.8, 0.53);
  const Pose2 kept = KeepPriorWhereUnconstrained(information, returns, pose, prior, 0.005, 0.5);
  EXPECT_NEAR(kept.x() - prior.x(), 0.1 / 1.5, 1e-12) << kept;
  EXPECT_NEAR(kept.y() - prior.y(), -0.2 / 3.0, 1e-12) << kept;
  EXPECT_NEAR(kept.theta() - prior.theta(), 0.03 / 1.5, 1e-12) << kept;
  const Pose2 across = KeepPriorWhereUnconstrained(information, returns, pose, prior, 0.3, 0.5);
  EXPECT_NEAR(across.x() - prior.x(), 0.1 / 1.5, 1e-12) << across;
  EXPECT_NEAR(across.y(), prior.y(), 1e-12) << across;
  // No weight and every share above the minimum: the pose as it was, to the bit.
  EXPECT_EQ(KeepPriorWhereUnconstrained(information, returns, pose, prior, 0.005, 0.0), pose);
  EXPECT_EQ(KeepPriorWhereUnconstrained(information, returns, pose, prior, 0.0, 0.0), pose);
}

TEST(ScanRefinementParamsTest, RejectsLimitsThatAreNegativeOrNotFinite) {
  ScanRefinementParams p;
  EXPECT_NO_THROW(ValidateScanRefinementParams(p));
  p.set_max_shift_cells(-0.1);
  EXPECT_THROW(ValidateScanRefinementParams(p), Error);
  p.set_max_shift_cells(1.0);
  p.set_max_turn_rad(std::numeric_limits<double>::infinity());
  EXPECT_THROW(ValidateScanRefinementParams(p), Error);
  p.set_max_turn_rad(0.02);
  p.set_iterations(10);
  p.set_wall_share(1.5);
  EXPECT_THROW(ValidateScanRefinementParams(p), Error);
  p.set_wall_share(std::nan(""));
  EXPECT_THROW(ValidateScanRefinementParams(p), Error);
  p.set_wall_share(0.0);
  EXPECT_NO_THROW(ValidateScanRefinementParams(p));
  p.set_iterations(100000);
  EXPECT_THROW(ValidateScanRefinementParams(p), Error);
}

}  // namespace
}  // namespace evoslam
