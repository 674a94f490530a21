#include "common/slam/loop_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <span>
#include <tuple>
#include <vector>

#include "common/sim/simulator.h"
#include "common/sim/trajectory.h"
#include "common/sim/world.h"
#include "common/slam/slam_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// A drive through the office cluster, its true poses, and the first scan that stands within
// 0.3 m of a scan at least 100 scans before it.
struct Revisit {
  Dataset log;
  std::vector<Pose2> truth;
  std::size_t earlier = 0, later = 0;
};

Revisit DriveBack() {
  SimulationOptions sim;
  sim.laser.beams = 91;
  sim.max_scans = 300;
  Revisit r;
  r.log = Simulate(BuiltinWorld("office-cluster"), sim);
  for (const LaserScan& s : r.log.scans) r.truth.push_back(*s.true_pose);
  const auto revisit = testing::FirstRevisit(r.log, 100, 0.3);
  if (revisit) std::tie(r.earlier, r.later) = *revisit;
  EXPECT_GT(r.later, 0u) << "the route never comes back";
  return r;
}

TEST(LoopDetectorTest, ARevisitThatDoesNotFitIsALoopWithTheTrueRelativePose) {
  const Revisit r = DriveBack();
  // The trajectory has drifted: the current pose is 0.4 m and 0.1 rad off.
  std::vector<Pose2> poses(r.truth.begin(), r.truth.begin() + r.later + 1);
  poses.back() = poses.back() * Pose2(0.4, -0.2, 0.1);
  LoopDetectionParams params;
  const auto loop = DetectLoop(r.log.scans, poses, r.later, params);
  ASSERT_TRUE(loop.has_value());
  EXPECT_EQ(loop->constraint.later, r.later);
  EXPECT_LE(r.later - loop->constraint.earlier, r.later);
  const Pose2 truth = r.truth[loop->constraint.earlier].inverse() * r.truth[r.later];
  const Pose2 error = truth.inverse() * loop->constraint.relative;
  EXPECT_LT(error.translation().norm(), 0.05);
  EXPECT_LT(std::abs(error.theta()), 0.01);
  EXPECT_GE(loop->score, params.min_match_score());
}

TEST(LoopDetectorTest, ARevisitThatFitsIsNoLoop) {
  const Revisit r = DriveBack();
  const std::vector<Pose2> poses(r.truth.begin(), r.truth.begin() + r.later + 1);
  EXPECT_FALSE(DetectLoop(r.log.scans, poses, r.later, {}).has_value());
}

// A revisit just past the heading's fit tolerance, where the trajectory's pose explains the scan
// about as well as the match: a loop by the shift alone, none with a score margin. A drift the
// scan shows plainly stays a loop with the same margin.
TEST(LoopDetectorTest, AScoreMarginTakesARevisitTheTrajectoryExplainsAsFitting) {
  const Revisit r = DriveBack();
  std::vector<Pose2> poses(r.truth.begin(), r.truth.begin() + r.later + 1);
  poses.back() = poses.back() * Pose2(0.0, 0.0, 0.03);
  LoopDetectionParams params;
  params.set_fit_score_margin(0.0);
  ASSERT_TRUE(DetectLoop(r.log.scans, poses, r.later, params).has_value());
  params.set_fit_score_margin(0.15);  // the two score 0.97 and 0.86
  EXPECT_FALSE(DetectLoop(r.log.scans, poses, r.later, params).has_value());
  poses.back() = r.truth[r.later] * Pose2(0.4, -0.2, 0.1);
  EXPECT_TRUE(DetectLoop(r.log.scans, poses, r.later, params).has_value());
}

// A bare corridor 2 m wide round a 26 x 16 m block, as docs/worlds/ring-corridor.lines, with a
// 4 m laser, driven one lap from its south-west corner and back down its west side. The lap's
// end sees the outer corner of the ring; the place at its start saw the block's corner from the
// corridors. Turned inside out, the outer corner's two walls line up with the block's two faces,
// the scan standing inside the block, better than the place's few walls explain the true pose.
TEST(LoopDetectorTest, AMatchInsideTheWallsItLinesUpWithIsNoLoop) {
  const std::vector<Segment> walls = {
      {{0, 0}, {30, 0}},       {{30, 0}, {30, 20}},      {{30, 20}, {0, 20}},
      {{0, 20}, {0, 0}},       {{2.3, 2}, {27.2, 2}},    {{27.2, 2}, {28, 2.8}},
      {{28, 2.8}, {28, 16.7}}, {{28, 16.7}, {26.7, 18}}, {{26.7, 18}, {2.5, 18}},
      {{2.5, 18}, {2, 17.5}},  {{2, 17.5}, {2, 2.3}},    {{2, 2.3}, {2.3, 2}}};
  SimulationOptions sim;
  sim.laser.beams = 361;
  sim.laser.max_range = 4.0;
  sim.max_scans = 1701;
  const Dataset log = Simulate(
      WorldFromLineMap(LineMap(walls), "ring", {{1, 1}, {29, 1}, {29, 19}, {1, 19}, {1, 1}}), sim);
  std::vector<Pose2> truth;
  for (const LaserScan& s : log.scans) truth.push_back(*s.true_pose);
  const std::size_t later = truth.size() - 1;
  ASSERT_LT((truth[later].translation() - Eigen::Vector2d(1.0, 2.27)).norm(), 0.1);

  LoopDetectionParams params;
  params.set_min_side_agreement(0.0);
  const auto inside_out = DetectLoop(log.scans, truth, later, params);
  ASSERT_TRUE(inside_out.has_value()) << "the look-alike is not found: the test sees nothing";
  const Pose2 true_relative = truth[inside_out->constraint.earlier].inverse() * truth[later];
  EXPECT_GT((inside_out->constraint.relative.translation() - true_relative.translation()).norm(),
            2.0);
  EXPECT_FALSE(DetectLoop(log.scans, truth, later, {}).has_value());
}

TEST(LoopDetectorTest, RecentPosesAndFarPlacesAreNoRevisit) {
  const Revisit r = DriveBack();
  std::vector<Pose2> poses(r.truth.begin(), r.truth.begin() + r.later + 1);
  poses.back() = poses.back() * Pose2(0.4, -0.2, 0.1);
  LoopDetectionParams params;
  params.set_min_travel_m(1e6);  // every earlier pose is too recent
  EXPECT_FALSE(DetectLoop(r.log.scans, poses, r.later, params).has_value());
  params = {};
  params.set_min_match_score(1.0);  // no match is that good
  EXPECT_FALSE(DetectLoop(r.log.scans, poses, r.later, params).has_value());
  poses.back() = Pose2(100.0, 100.0, 0.0);  // nowhere near the path
  EXPECT_FALSE(DetectLoop(r.log.scans, poses, r.later, {}).has_value());
}

TEST(LoopDetectorTest, TheWindowGrowsWithThePathBetweenTheVisitsUpToItsLargest) {
  LoopDetectionParams params;
  params.set_match_window_m(1.5);
  params.set_match_window_per_m(0.02);
  params.set_max_match_window_m(3.0);
  EXPECT_EQ(MatchWindow(params, 10.0), 1.5);
  EXPECT_DOUBLE_EQ(MatchWindow(params, 100.0), 2.0);
  EXPECT_EQ(MatchWindow(params, 1000.0), 3.0);
  params.set_match_window_per_m(0.0);
  EXPECT_EQ(MatchWindow(params, 1000.0), 1.5);
}

// The drive back, with the revisiting pose moved (dx, dy) and 0.05 rad off, as after a long
// loop; `path` is the true path between the two visits.
struct FarRevisit {
  Revisit r;
  std::vector<Pose2> poses;
  double path = 0.0;
};

FarRevisit DriveBackFarOff(double dx, double dy) {
  FarRevisit f{DriveBack(), {}, 0.0};
  const Revisit& r = f.r;
  f.poses.assign(r.truth.begin(), r.truth.begin() + r.later + 1);
  const Pose2 at = f.poses.back();
  f.poses.back() = Pose2(at.x() + dx, at.y() + dy, at.theta() + 0.05);
  f.path = PathLength(std::span(r.truth).subspan(r.earlier, r.later - r.earlier + 1));
  return f;
}

// The loop's relative pose is the true one, within 5 cm and a degree (eq. 7 uses the
// translation only).
void ExpectTrueRelativePose(const Revisit& r, const LoopClosure& loop) {
  const Pose2 truth = r.truth[loop.constraint.earlier].inverse() * r.truth[r.later];
  const Pose2 error = truth.inverse() * loop.constraint.relative;
  EXPECT_LT(error.translation().norm(), 0.05);
  EXPECT_LT(std::abs(error.theta()), 0.02);
}

// A revisit 2.4 m off, as on ACES after a long loop: beyond the fixed window and radius, found
// once they grow with the path.
TEST(LoopDetectorTest, ARevisitFarOffAfterALongPathIsFoundOnlyWithTheGrowingWindow) {
  const FarRevisit f = DriveBackFarOff(2.0, -1.3);
  LoopDetectionParams params;
  params.set_match_window_per_m(0.0);
  EXPECT_FALSE(DetectLoop(f.r.log.scans, f.poses, f.r.later, params).has_value());
  params.set_match_window_per_m(params.max_match_window_m() / f.path);
  const auto loop = DetectLoop(f.r.log.scans, f.poses, f.r.later, params);
  ASSERT_TRUE(loop.has_value());
  ExpectTrueRelativePose(f.r, *loop);
}

// A revisit 3.9 m off, as ACES's pass at scan 4,880 through the place of scan 2,370: beyond a
// window that stops at 3 m, found within the default largest window.
TEST(LoopDetectorTest, ARevisitFourMetresOffIsFoundOnlyWithinTheLargestWindow) {
  const FarRevisit f = DriveBackFarOff(3.4, -1.9);
  LoopDetectionParams params;
  ASSERT_GE(params.max_match_window_m(), 5.0);
  params.set_match_window_per_m(params.max_match_window_m() / f.path);
  const auto loop = DetectLoop(f.r.log.scans, f.poses, f.r.later, params);
  ASSERT_TRUE(loop.has_value());
  ExpectTrueRelativePose(f.r, *loop);
  params.set_max_match_window_m(3.0);
  params.set_match_window_per_m(params.max_match_window_m() / f.path);
  EXPECT_FALSE(DetectLoop(f.r.log.scans, f.poses, f.r.later, params).has_value());
}

TEST(LoopDetectorTest, RefusesBadParametersAndScansWithoutPoses) {
  const Revisit r = DriveBack();
  const std::vector<Pose2> poses(r.truth.begin(), r.truth.begin() + 10);
  EXPECT_THROW(DetectLoop(r.log.scans, poses, 10, {}), Error);
  LoopDetectionParams params;
  params.set_min_match_score(1.5);
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
  params = {};
  params.set_revisit_radius_m(0.0);
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
  params = {};
  params.set_min_gap_scans(0);
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
  params = {};
  params.set_match_window_per_m(std::numeric_limits<double>::infinity());
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
  params = {};
  params.set_max_match_window_m(params.match_window_m() - 0.1);
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
  params = {};
  params.set_fit_score_margin(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
  params = {};
  params.set_min_side_agreement(1.01);
  EXPECT_THROW(ValidateLoopDetectionParams(params), Error);
}

// A shift fits when it is within both tolerances, as eq. 7 measures a loop's miss, so a loop
// that a search closed does not fit any worse at the next check.
TEST(FitsWhereItIsTest, WithinBothTolerances) {
  LoopDetectionParams params;
  params.set_fit_tolerance_m(0.1);
  params.set_fit_tolerance_rad(0.02);
  EXPECT_TRUE(FitsWhereItIs(Pose2(0.06, -0.079, 0.02), params));
  EXPECT_FALSE(FitsWhereItIs(Pose2(0.07, -0.08, 0.0), params));
  EXPECT_FALSE(FitsWhereItIs(Pose2(0.0, 0.0, 0.021), params));
}

}  // namespace
}  // namespace evoslam
