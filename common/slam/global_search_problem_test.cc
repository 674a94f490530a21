#include "common/slam/global_search_problem.h"

#include <gtest/gtest.h>

#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(GlobalSearchProblemTest, TheIdentityChangesNothingAndErrorsSpreadOverTheirPartition) {
  SimulationOptions sim;
  sim.laser.beams = 31;
  sim.max_scans = 30;
  const struct { Dataset log; } loop{Simulate(BuiltinWorld("office-cluster"), sim)};
  const std::size_t n = 30;
  std::vector<Pose2> odometry;
  for (std::size_t i = 0; i < n; ++i) odometry.push_back(loop.log.scans[i].odometry);
  const HitCountGrid base(0.05, Eigen::Vector2d(-2, -2), 600, 460);
  GlobalSearchParams params;
  params.partitions = 3;
  const GlobalSearchProblem problem(loop.log.scans, odometry, 10, n, base, params, std::nullopt);
  EXPECT_EQ(problem.lower().size(), 18);
  const std::vector<Pose2> same = problem.Apply(problem.Identity());
  ASSERT_EQ(same.size(), n - 10);
  for (std::size_t k = 0; k < same.size(); ++k) {
    EXPECT_NEAR((same[k].translation() - odometry[10 + k].translation()).norm(), 0.0, 1e-9);
  }
  // A heading error in the first partition turns everything after it by exactly that much.
  Eigen::VectorXd x = problem.Identity();
  x(4) = 0.1;
  const std::vector<Pose2> turned = problem.Apply(x);
  EXPECT_NEAR(WrapAngle(turned.back().theta() - odometry.back().theta()), 0.1, 1e-9);
  EXPECT_THROW(GlobalSearchProblem(loop.log.scans, odometry, 10, n + 1, base, params, std::nullopt),
               Error);
}

}  // namespace
}  // namespace evoslam
