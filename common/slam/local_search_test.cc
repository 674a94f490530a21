#include "common/slam/local_search.h"

#include <gtest/gtest.h>

#include <cmath>

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
  HitCountGrid a = EmptyMapFor(d, params), b = EmptyMapFor(d, params);
  const auto ra = RunLocalSearch(d, params, 5, a), rb = RunLocalSearch(d, params, 5, b);
  for (std::size_t i = 0; i < ra.trajectory.size(); ++i)
    EXPECT_EQ(ra.trajectory[i].pose, rb.trajectory[i].pose);
  params.particles = 1;
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
  params.recentres = 0;
  const StepCorrection once = CorrectStep(map, scan, predicted, params, Rng(3));
  EXPECT_GT(heading_error(once.pose), 0.025);
  params.recentres = 2;
  const StepCorrection recentred = CorrectStep(map, scan, predicted, params, Rng(3));
  EXPECT_LT(heading_error(recentred.pose), 0.01);
  EXPECT_LT(distance(recentred.pose), 0.06);
  EXPECT_GT(recentred.evaluations, once.evaluations);
  // Where the first cube holds the optimum, no second search runs.
  const StepCorrection near =
      CorrectStep(map, scan, truth * Pose2(0.03, 0.02, 0.01), params, Rng(3));
  EXPECT_EQ(near.evaluations, once.evaluations);
  EXPECT_LT(heading_error(near.pose), 0.01);
}

}  // namespace
}  // namespace evoslam
