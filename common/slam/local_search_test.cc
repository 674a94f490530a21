#include "common/slam/local_search.h"

#include <gtest/gtest.h>

#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"

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

}  // namespace
}  // namespace evoslam
