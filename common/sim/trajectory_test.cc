#include "common/sim/trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/util/error.h"

namespace evoslam {
namespace {

using std::numbers::pi;
using ::testing::HasSubstr;

TEST(SmoothPathTest, StraightLineIsEvenlySampled) {
  const std::vector<Eigen::Vector2d> waypoints = {{0, 0}, {3, 4}};
  const std::vector<Pose2> path = SmoothPath(waypoints, {.step = 0.1});
  ASSERT_EQ(path.size(), 51u);  // 5 m in 50 steps, both ends included
  EXPECT_TRUE(path.front().translation().isApprox(Eigen::Vector2d(0, 0)));
  EXPECT_TRUE(path.back().translation().isApprox(Eigen::Vector2d(3, 4)));
  for (std::size_t i = 0; i < path.size(); ++i) {
    EXPECT_NEAR(path[i].theta(), std::atan2(4.0, 3.0), 1e-12);
    if (i > 0) {
      EXPECT_NEAR((path[i].translation() - path[i - 1].translation()).norm(), 0.1, 1e-9);
    }
  }
  EXPECT_NEAR(PathLength(path), 5.0, 1e-9);
}

TEST(SmoothPathTest, RoundsCornersWithArcs) {
  const std::vector<Eigen::Vector2d> waypoints = {{0, 0}, {5, 0}, {5, 5}};
  const std::vector<Pose2> path = SmoothPath(waypoints, {.step = 0.02, .turn_radius = 0.5});
  EXPECT_TRUE(path.front().translation().isApprox(Eigen::Vector2d(0, 0)));
  EXPECT_TRUE(path.back().translation().isApprox(Eigen::Vector2d(5, 5)));
  // The arc is tangent to both legs with its centre at (4.5, 0.5); it passes the corner at
  // 0.5 (sqrt(2) - 1).
  double closest = 1e9;
  for (const Pose2& p : path) {
    const Eigen::Vector2d q = p.translation();
    closest = std::min(closest, (q - Eigen::Vector2d(5, 0)).norm());
    if (q.x() > 4.5 + 1e-9 && q.y() < 0.5 - 1e-9) {
      EXPECT_NEAR((q - Eigen::Vector2d(4.5, 0.5)).norm(), 0.5, 1e-9);
      // Heading along the arc: perpendicular to the radius.
      EXPECT_NEAR(p.theta(), std::atan2(q.x() - 4.5, 0.5 - q.y()), 1e-9);
    }
  }
  EXPECT_NEAR(closest, 0.5 * (std::sqrt(2.0) - 1.0), 0.01);
  // Heading turns monotonically from 0 to 90 degrees.
  for (std::size_t i = 1; i < path.size(); ++i) {
    EXPECT_GE(path[i].theta(), path[i - 1].theta() - 1e-12);
  }
  EXPECT_NEAR(path.back().theta(), pi / 2, 1e-12);
  // Length: two 4.5 m straights and a quarter circle of radius 0.5.
  EXPECT_NEAR(PathLength(path), 9.0 + pi / 4, 1e-3);
}

TEST(SmoothPathTest, ShortLegsShrinkTheArc) {
  // Legs of 0.4 m leave room for an arc of at most 0.2 m each side of the inner corner.
  const std::vector<Eigen::Vector2d> waypoints = {{0, 0}, {2, 0}, {2, 0.4}, {0, 0.4}};
  const std::vector<Pose2> path = SmoothPath(waypoints, {.step = 0.01, .turn_radius = 1.0});
  for (const Pose2& p : path) {
    EXPECT_LE(p.x(), 2.0 + 1e-9);
    EXPECT_GE(p.y(), -1e-9);
    EXPECT_LE(p.y(), 0.4 + 1e-9);
  }
  EXPECT_NEAR(std::abs(path.back().theta()), pi, 1e-9);
}

TEST(SmoothPathTest, ReversalTurnsOnTheSpot) {
  const std::vector<Eigen::Vector2d> waypoints = {{0, 0}, {2, 0}, {0, 0}};
  const PathOptions options{.step = 0.05, .min_turn_sampling_radius = 0.3};
  const std::vector<Pose2> path = SmoothPath(waypoints, options);
  int at_tip = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if ((path[i].translation() - Eigen::Vector2d(2, 0)).norm() < 1e-9) ++at_tip;
    if (i > 0) {
      // Heading changes are spread: at most step / sampling radius per pose.
      EXPECT_LE(std::abs(WrapAngle(path[i].theta() - path[i - 1].theta())), 0.05 / 0.3 + 1e-6);
    }
  }
  EXPECT_GE(at_tip, static_cast<int>(pi * 0.3 / 0.05) - 1);
  EXPECT_NEAR(std::abs(path.back().theta()), pi, 1e-9);
}

TEST(SmoothPathTest, RejectsBadInput) {
  const std::vector<Eigen::Vector2d> one = {{1, 1}};
  const std::vector<Eigen::Vector2d> same = {{1, 1}, {1, 1}};
  const std::vector<Eigen::Vector2d> nan = {{0, 0}, {std::nan(""), 1}};
  const std::vector<Eigen::Vector2d> good = {{0, 0}, {1, 1}};
  EXPECT_THROW(SmoothPath(one), Error);
  EXPECT_THROW(SmoothPath(same), Error);
  EXPECT_THROW(SmoothPath(nan), Error);
  EXPECT_THROW(SmoothPath(good, {.step = 0.0}), Error);
  EXPECT_THROW(SmoothPath(good, {.turn_radius = -1.0}), Error);
}

TEST(MeasureClearanceTest, FindsClosestApproach) {
  // A post at (3, 0) and a far wall; the path passes the post 0.99 m away, mid-piece.
  const LineMap map({{{3, 0}, {3, 0.01}}, {{20, 20}, {21, 20}}});
  const std::vector<Pose2> path = {{0, 1, 0}, {2, 1, 0}, {4, 1, 0}, {6, 2, 0}};
  const PathClearance clearance = MeasureClearance(map, path, 5.0);
  EXPECT_NEAR(clearance.distance, 0.99, 1e-12);
  EXPECT_EQ(clearance.pose, 1u);
  EXPECT_EQ(MeasureClearance(map, path, 0.5).distance, 0.5);  // nothing within the limit
}

TEST(RouteTrajectoryTest, BuiltinRoutesKeepClearOfWallsWithPaperScanCounts) {
  const struct {
    const char* name;
    double scans;  // as logged in the experiments
  } expected[] = {{"office-boxes", 350},
                  {"s-corridor", 219},
                  {"static-objects", 350},
                  {"office-cluster", 1832}};
  for (const auto& e : expected) {
    const World world = BuiltinWorld(e.name);
    const std::vector<Pose2> path = RouteTrajectory(world, world.scan_spacing);
    EXPECT_GE(MeasureClearance(world.map, path, 1.0).distance, kMinWallClearance) << e.name;
    EXPECT_NEAR(static_cast<double>(path.size()), e.scans, 0.05 * e.scans) << e.name;
  }
  const World empty = BuiltinWorld("empty-room");
  EXPECT_GE(MeasureClearance(empty.map, RouteTrajectory(empty, 0.05), 1.0).distance,
            kMinWallClearance);
}

TEST(RouteTrajectoryTest, PathLengthsMatchThePapers) {
  const World corridor = BuiltinWorld("s-corridor");
  EXPECT_NEAR(PathLength(RouteTrajectory(corridor, 0.05)), 11.56, 0.6);
  const World cluster = BuiltinWorld("office-cluster");
  EXPECT_NEAR(PathLength(RouteTrajectory(cluster, 0.1)), 236.3, 12.0);
}

TEST(RouteTrajectoryTest, AutoRoutesKeepClearOfWalls) {
  for (const std::string& name : BuiltinWorldNames()) {
    const World world = WorldFromLineMap(BuiltinWorld(name).map, name);
    const std::vector<Pose2> path = RouteTrajectory(world, 0.1);
    EXPECT_GE(MeasureClearance(world.map, path, 1.0).distance, kMinWallClearance) << name;
  }
}

TEST(RouteTrajectoryTest, RouteThroughAWallFailsNamingTheWorld) {
  const World world{"blocked", LineMap({{{1, -1}, {1, 1}}}), {{0, 0}, {2, 0}}};
  try {
    RouteTrajectory(world, 0.05);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("blocked"));
    EXPECT_THAT(e.what(), HasSubstr("0.000 m from a wall"));
  }
}

}  // namespace
}  // namespace evoslam
