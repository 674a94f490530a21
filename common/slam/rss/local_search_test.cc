#include "common/slam/rss/local_search.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/line_map/line_map.h"
#include "common/localization/test_scenes.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

TEST(LocalSearchTest, TheSameSeedGivesTheSameTrajectory) {
  SimulationOptions sim;
  sim.max_scans = 20;
  const Dataset d = Simulate(BuiltinWorld("s-corridor"), sim);
  LocalSearchParams params;
  HitCountGrid a = EmptyMapFor(d, {}, params), b = EmptyMapFor(d, {}, params);
  const auto ra = RunLocalSearch(d, params, 5, a), rb = RunLocalSearch(d, params, 5, b);
  for (std::size_t i = 0; i < ra.trajectory.size(); ++i)
    EXPECT_EQ(ra.trajectory[i].pose, rb.trajectory[i].pose);
  params.set_particles(1);
  EXPECT_THROW(RunLocalSearch(d, params, 5, a), Error);
}

// A step whose odometry turned more than the cube allows: one search stops on the cube's face,
// a search recentred there reaches the true heading.
TEST(CorrectStepTest, RecentredSearchesReachAnErrorBeyondTheCube) {
  const LineMap room = testing::BoxRoom();
  HitCountGrid map(0.05, Eigen::Vector2d(-1.0, -1.0), 180, 200);
  for (int i = 0; i < 5; ++i) {
    const Pose2 pose(2.5 + 0.1 * i, 2.0 + 0.08 * i, 0.55 + 0.04 * i);
    map.AddScan(testing::ScanFrom(room, pose), pose);
  }
  const Pose2 truth(3.1, 2.5, 0.8);
  const LaserScan scan = testing::ScanFrom(room, truth);
  const Pose2 predicted = truth * Pose2(0.03, -0.04, 0.08);  // 1.6 times the cube in heading
  const auto heading_error = [&](const Pose2& p) { return std::abs(p.theta() - truth.theta()); };
  const auto distance = [&](const Pose2& p) {
    return (p.translation() - truth.translation()).norm();
  };

  LocalSearchParams params;
  params.mutable_refine()->set_iterations(0);  // the PSO's pose, which the refinement would move on
  params.set_recentres(0);
  const StepCorrection once =
      CorrectStep(map, scan, predicted, BaseErrorCube(params), params, Rng(3));
  EXPECT_GT(heading_error(once.pose), 0.025);
  params.set_recentres(2);
  const StepCorrection recentred =
      CorrectStep(map, scan, predicted, BaseErrorCube(params), params, Rng(3));
  EXPECT_LT(heading_error(recentred.pose), 0.01);
  EXPECT_LT(distance(recentred.pose), 0.06);
  EXPECT_GT(recentred.evaluations, once.evaluations);
  // Where the first cube holds the optimum, no second search runs.
  const StepCorrection near = CorrectStep(map, scan, truth * Pose2(0.03, 0.02, 0.01),
                                          BaseErrorCube(params), params, Rng(3));
  EXPECT_EQ(near.evaluations, once.evaluations);
  EXPECT_LT(heading_error(near.pose), 0.01);
}

TEST(StepErrorCubeTest, TheHeadingRangeGrowsWithTheTurnOdometryReports) {
  LocalSearchParams params;
  params.set_max_error_y_m(0.08);
  params.set_heading_range_per_turn(0.5);
  params.set_heading_range_per_correction(0.25);
  const Eigen::Vector3d base(0.1, 0.08, 0.05);
  EXPECT_EQ(BaseErrorCube(params), base);
  EXPECT_EQ(StepErrorCube(params, Pose2(0.3, 0.0, 0.0), 0.0), base);
  const Eigen::Vector3d turning = StepErrorCube(params, Pose2(0.1, 0.0, -0.4), 0.0);
  EXPECT_EQ(turning.head<2>(), base.head<2>());
  EXPECT_DOUBLE_EQ(turning.z(), 0.05 + 0.5 * 0.4);
  // ...and with the heading correction the step before took, whichever its sign.
  const Eigen::Vector3d after_correction = StepErrorCube(params, Pose2(0.1, 0.0, -0.4), -0.2);
  EXPECT_EQ(after_correction.head<2>(), base.head<2>());
  EXPECT_DOUBLE_EQ(after_correction.z(), 0.05 + 0.5 * 0.4 + 0.25 * 0.2);
  EXPECT_EQ(StepErrorCube(params, Pose2(0.1, 0.0, -0.4), 0.2), after_correction);
}

// The box room's map from five scans 0.1 m apart, driven straight up to `end`.
HitCountGrid MapDrivenUpTo(const LineMap& room, const Pose2& end) {
  HitCountGrid map(0.05, Eigen::Vector2d(-1.0, -1.0), 180, 200);
  for (int i = 0; i < 5; ++i) {
    const Pose2 pose = end * Pose2(-0.1 * (4 - i), 0.0, 0.0);
    map.AddScan(testing::ScanFrom(room, pose), pose);
  }
  return map;
}

// A fast turn whose odometry overstates it by 0.25 rad, more than two recentred cubes of
// +-0.05 rad reach: only a heading range that grows with the turn finds the true heading.
TEST(CorrectLogStepTest, AFastTurnsHeadingErrorIsFoundWhenTheCubeGrowsWithTheTurn) {
  const LineMap room = testing::BoxRoom();
  const Pose2 start(2.8, 2.2, 0.3);
  const HitCountGrid map = MapDrivenUpTo(room, start);
  const Pose2 truth = start * Pose2(0.05, 0.0, 0.9);
  Dataset drive;
  drive.scans = {testing::ScanFrom(room, start), testing::ScanFrom(room, truth)};
  drive.scans[0].odometry = start;
  drive.scans[1].odometry = start * Pose2(0.05, 0.0, 0.9 + 0.25);
  const auto heading_error = [&](double per_rad) {
    LocalSearchParams params;
    params.set_heading_range_per_turn(per_rad);
    const std::vector<Pose2> poses{start};
    const StepCorrection c = CorrectLogStep(map, drive, poses, params, Rng(4));
    return std::abs((truth.inverse() * c.pose).theta());
  };
  EXPECT_GT(heading_error(0.0), 0.05);
  EXPECT_LT(heading_error(0.6), 0.01);
}

// Two steps of 0.3 rad through the box room. Odometry put 0.2 rad more into the first, and the
// local search took it back; the second step's odometry is the test's.
struct TurnAfterACorrection {
  HitCountGrid map;
  Dataset drive;
  std::vector<Pose2> poses;  // the first two scans', the second corrected by -0.2 rad
  Pose2 second;              // the third scan's true pose
};

TurnAfterACorrection MakeTurnAfterACorrection() {
  const LineMap room = testing::BoxRoom();
  const Pose2 start(2.8, 2.2, 0.3);
  const Pose2 first = start * Pose2(0.05, 0.0, 0.3);
  TurnAfterACorrection t{
      MapDrivenUpTo(room, start), {}, {start, first}, first * Pose2(0.05, 0.0, 0.3)};
  t.map.AddScan(testing::ScanFrom(room, first), first);
  t.drive.scans = {testing::ScanFrom(room, start), testing::ScanFrom(room, first),
                   testing::ScanFrom(room, t.second)};
  t.drive.scans[0].odometry = start;
  t.drive.scans[1].odometry = start * Pose2(0.05, 0.0, 0.3 + 0.2);
  return t;
}

// Odometry read a little after the laser during a turn: it puts 0.2 rad of the second step's
// turn into the first. The first step's correction took that back; the second step's error, the
// opposite, lies beyond a cube sized by the little turn odometry reports for it, but within one
// that also allows for the correction before.
TEST(CorrectLogStepTest, AHeadingCorrectionTakenOneStepIsAllowedForInTheNext) {
  TurnAfterACorrection t = MakeTurnAfterACorrection();
  t.drive.scans[2].odometry = t.drive.scans[1].odometry * Pose2(0.05, 0.0, 0.3 - 0.2);
  const auto heading_error = [&](double carried, double shift) {
    LocalSearchParams params;  // the cube alone: 0.05 + 0.6 * 0.1 rad without the carry
    params.set_recentres(0);
    params.mutable_refine()->set_iterations(0);
    params.set_heading_range_per_correction(carried);
    params.set_heading_shift_per_correction(shift);
    const StepCorrection c = CorrectLogStep(t.map, t.drive, t.poses, params, Rng(4));
    return std::abs((t.second.inverse() * c.pose).theta());
  };
  EXPECT_GT(heading_error(0.0, 0.0), 0.05);
  EXPECT_LT(heading_error(0.5, 0.0), 0.01);
  // Moved by the 0.2 rad owed, a cube no wider than the turn makes it holds the step's heading;
  // moved the other way, it cannot.
  EXPECT_LT(heading_error(0.0, 1.0), 0.01);
  EXPECT_GT(heading_error(0.0, -1.0), 0.05);
}

// The same turn with the whole correction carried over as a shift. Where odometry gives the
// 0.2 rad back, the shift centres the heading range on the step's heading. Where odometry is
// right, it moves the range 0.2 rad away, out of a cube of +-0.05 rad, and a second swarm centred
// on odometry's heading finds the step; where the shift guessed right, its swarm's fit is kept.
TEST(CorrectLogStepTest, ASecondSwarmAtOdometrysHeadingHedgesAShiftThatGuessesWrong) {
  TurnAfterACorrection t = MakeTurnAfterACorrection();
  const auto heading_error = [&](double given_back, double hedged_shift) {
    t.drive.scans[2].odometry = t.drive.scans[1].odometry * Pose2(0.05, 0.0, 0.3 - given_back);
    LocalSearchParams params;
    params.set_recentres(0);
    params.mutable_refine()->set_iterations(0);
    params.set_heading_range_per_turn(0.0);
    params.set_heading_range_per_correction(0.0);
    params.set_heading_shift_per_correction(1.0);
    params.set_second_swarm_above_rad(hedged_shift);
    const StepCorrection c = CorrectLogStep(t.map, t.drive, t.poses, params, Rng(4));
    return std::abs((t.second.inverse() * c.pose).theta());
  };
  EXPECT_GT(heading_error(0.0, 0.0), 0.04);
  EXPECT_LT(heading_error(0.0, 0.05), 0.01);
  EXPECT_GT(heading_error(0.0, 0.25), 0.04);  // a shift of 0.2 rad is not hedged from 0.25
  EXPECT_LT(heading_error(0.2, 0.0), 0.01);
  EXPECT_LT(heading_error(0.2, 0.05), 0.01);
}

TEST(CorrectLogStepTest, RefusesAStepWithoutAPoseBeforeIt) {
  const LineMap room = testing::BoxRoom();
  Dataset drive;
  drive.scans = {testing::ScanFrom(room, Pose2(2.8, 2.2, 0.0)),
                 testing::ScanFrom(room, Pose2(2.9, 2.2, 0.0))};
  const HitCountGrid map(0.05, Eigen::Vector2d(-1.0, -1.0), 100, 100);
  EXPECT_THROW(CorrectLogStep(map, drive, {}, LocalSearchParams{}, Rng(1)), Error);
  const std::vector<Pose2> all(drive.scans.size());
  EXPECT_THROW(CorrectLogStep(map, drive, all, LocalSearchParams{}, Rng(1)), Error);
}

// Two scans whose positions lie more than twice the laser's reach apart can see no point in
// common; at exactly twice they still can.
TEST(CheckOdometryStepsTest, RefusesAStepFartherThanTwiceTheLasersReach) {
  const LineMap room = testing::BoxRoom();
  Dataset drive;
  drive.source = "drive.clf";
  for (int i = 0; i < 3; ++i) drive.scans.push_back(testing::ScanFrom(room, Pose2(2.8, 2.2, 0.0)));
  drive.scans[1].odometry = Pose2(0.0, 0.0, 0.0);
  drive.scans[2].odometry = Pose2(16.0, 0.0, 0.0);  // the laser reaches 8 m
  EXPECT_NO_THROW(CheckOdometrySteps(drive));
  drive.scans[2].odometry = Pose2(16.01, 0.0, 0.0);
  try {
    CheckOdometrySteps(drive);
    ADD_FAILURE() << "a 16.01 m step with an 8 m laser was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("drive.clf"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("from scan 1 to scan 2"));
  }
  drive.scans[2].odometry = Pose2(1e300, 0.0, 0.0);
  EXPECT_THROW(CheckOdometrySteps(drive), Error);
  drive.scans[2].odometry = Pose2(std::nan(""), 0.0, 0.0);
  EXPECT_THROW(CheckOdometrySteps(drive), Error);
}

// A map too large for the search's grid is refused by name and extent, not by the grid's own
// check on a size that has overflowed.
TEST(EmptyMapForTest, RefusesAMapOfMoreCellsThanTheGridHolds) {
  const LineMap room = testing::BoxRoom();
  Dataset drive;
  drive.source = "drive.clf";
  drive.scans = {testing::ScanFrom(room, Pose2(2.8, 2.2, 0.0))};
  proto::RssMap params;
  params.set_margin_m(0.0);
  params.set_cell_size_m(0.05);
  EXPECT_EQ(EmptyMapFor(drive, params, {}).width(), 321);  // 8 m either side, 5 cm cells
  params.set_cell_size_m(1e-4);                            // 160,001^2 cells
  try {
    EmptyMapFor(drive, params, {});
    ADD_FAILURE() << "a map of more than HitCountGrid::kMaxCells cells was made";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("drive.clf"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("coarser resolution"));
  }
  drive.scans.push_back(drive.scans[0]);
  drive.scans[1].odometry = Pose2(1e300, 0.0, 0.0);  // would overflow an int count
  params.set_cell_size_m(0.05);
  EXPECT_THROW(EmptyMapFor(drive, params, {}), Error);
}

// Down a hall longer than the laser's reach every scan sees its walls a step farther on. The end
// points past the previous scan's reach land off the map whatever the pose, and fewer of them do
// the shorter the step: scored, they pull every step short.
TEST(LocalSearchTest, DownAHallLongerThanTheLasersReachTheFrontierDoesNotPullTheStepsShort) {
  constexpr double kHalfWidth = 2.5;
  std::vector<Segment> walls{{{-2.0, -kHalfWidth}, {40.0, -kHalfWidth}},
                             {{-2.0, kHalfWidth}, {40.0, kHalfWidth}}};
  for (double x = 0.5; x < 40.0; x += 2.6) {  // door frames, so that a step is observable
    walls.push_back({{x, -kHalfWidth}, {x, 0.1 - kHalfWidth}});
    walls.push_back({{x + 1.3, kHalfWidth}, {x + 1.3, kHalfWidth - 0.1}});
  }
  const LineMap corridor(std::move(walls));
  Dataset drive;
  for (int i = 0; i < 100; ++i) {
    const Pose2 pose(0.2 * i, 0.0, 0.0);
    LaserScan scan = testing::ScanFrom(corridor, pose, 181, 4.0);
    scan.timestamp = i;
    scan.odometry = pose;
    drive.scans.push_back(std::move(scan));
  }
  const auto shortfall = [&](double margin, double pull = LocalSearchParams{}.odometry_tie_pull()) {
    LocalSearchParams params;
    params.set_reach_margin_m(margin);
    params.set_odometry_tie_pull(pull);
    // The score's pull alone: the refinement, drawn to the wall's mapped end, adds its own (with 5
    // cm cells, 5.1 against 3.3 m short with every return scored).
    params.mutable_refine()->set_iterations(0);
    // Ties go to the heading range's centre, which the carried-turn shift moves off odometry; on
    // this flat score the heading then wanders a little, and the pull is measured against
    // odometry itself (with the shift: 0.58 against 0.45 m short without the pull).
    params.set_heading_shift_per_correction(0.0);
    HitCountGrid map = EmptyMapFor(drive, {}, params);
    const LocalSearchResult r = RunLocalSearch(drive, params, 1, map);
    return drive.scans.back().odometry.x() - r.trajectory.back().pose.x();
  };
  // The odometry is exact, so any shortfall is the score's pull. What remains with the frontier
  // left out comes from the wall each door frame hid from the previous scan.
  const double all = shortfall(-1.0), within = shortfall(LocalSearchParams{}.reach_margin_m());
  EXPECT_GT(all, 2.0);
  EXPECT_LT(std::abs(within), all / 3) << "every return scored: " << all << " m short";
  // Where the frame's hidden wall leaves the score flat, the swarm's pick among equal counts
  // wanders; the odometry pull keeps such steps where odometry puts them (0.06 against 0.2 m).
  const double unpulled = shortfall(LocalSearchParams{}.reach_margin_m(), 0.0);
  EXPECT_LT(std::abs(within), 0.75 * unpulled) << "without the pull: " << unpulled << " m short";
}

// A hall with nothing on its walls, longer than the laser's reach: each scan fixes its step
// across the hall and its heading, and nothing along it. Odometry that over-reads by 2 % is the
// only measure along the hall. Keeping the prediction there, a search ends about as far off as
// odometry; taking the swarm's pick, which eq. 1's pull back into the mapped part of the walls
// biases, it slides short by more than odometry's error.
TEST(LocalSearchTest, DownAFeaturelessHallTheStepKeepsThePredictionAlongIt) {
  const LineMap hall(
      std::vector<Segment>{{{-2.0, -1.0}, {60.0, -1.0}}, {{-2.0, 1.0}, {60.0, 1.0}}});
  constexpr int kScans = 200;
  constexpr double kStep = 0.2;
  Dataset drive;
  for (int i = 0; i < kScans; ++i) {
    const Pose2 pose(kStep * i, 0.0, 0.0);
    LaserScan scan = testing::ScanFrom(hall, pose, 361, 4.0);
    scan.timestamp = i;
    scan.odometry = Pose2(1.02 * pose.x(), 0.0, 0.0);
    drive.scans.push_back(std::move(scan));
  }
  const double end = kStep * (kScans - 1);
  const double odometry_error = drive.scans.back().odometry.x() - end;
  const auto end_error = [&](double min_constraint_ratio, std::uint64_t seed) {
    LocalSearchParams params;
    params.set_odometry_below_information(min_constraint_ratio);
    HitCountGrid map = EmptyMapFor(drive, {}, params);
    return RunLocalSearch(drive, params, seed, map).trajectory.back().pose.x() - end;
  };
  double worst_kept = 0.0, worst_picked = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    worst_kept = std::max(
        worst_kept, std::abs(end_error(LocalSearchParams{}.odometry_below_information(), seed)));
    worst_picked = std::max(worst_picked, std::abs(end_error(0.0, seed)));
  }
  EXPECT_LT(worst_kept, odometry_error + 0.1) << "odometry " << odometry_error << " m off";
  EXPECT_GT(worst_picked, odometry_error + 0.3)
      << "the swarm's pick did not slide: the hall shows nothing";
}

TEST(WithinPreviousReachTest, DropsTheReturnsBeyondThePreviousScansReach) {
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = std::numbers::pi / 2;
  scan.range_max = 5.0;
  scan.ranges = {4.0, 4.5, 3.0};  // ahead, left, behind
  LaserScan previous = scan;
  // One metre behind along x: ahead lies 5 m away, left 4.61 m, behind 2 m.
  const Pose2 pose(1.0, 0.0, 0.0), previous_pose(0.0, 0.0, 0.0);
  const LaserScan scored = WithinPreviousReach(scan, pose, previous, previous_pose, 0.2);
  EXPECT_FALSE(scored.is_return(0));
  EXPECT_TRUE(scored.is_return(1));
  EXPECT_TRUE(scored.is_return(2));
  EXPECT_EQ(scored.ranges[1], scan.ranges[1]);
  EXPECT_FALSE(WithinPreviousReach(scan, pose, previous, previous_pose, 0.5).is_return(1));
  const LaserScan all = WithinPreviousReach(scan, pose, previous, previous_pose, -1.0);
  EXPECT_EQ(all.ranges, scan.ranges);
}

}  // namespace
}  // namespace evoslam
