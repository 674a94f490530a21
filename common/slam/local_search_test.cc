#include "common/slam/local_search.h"

#include <gtest/gtest.h>

#include "common/eval/trajectory_errors.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Root-mean-square distance of a trajectory's positions from the truth.
double Ate(const std::vector<StampedPose>& trajectory, const Dataset& d) {
  std::vector<StampedPose> truth;
  for (const LaserScan& s : d.scans) truth.push_back({s.timestamp, *s.true_pose});
  return ComputeAbsoluteErrors(trajectory, truth).rms_translation;
}

TEST(LocalSearchTest, CorrectsDriftingOdometryOnARealisticRoute) {
  SimulationOptions sim;
  sim.noise.gaussian_sigma = 0.01;
  sim.noise.odometry.rotation_bias = 0.02;  // a strong heading drift
  sim.max_scans = 150;
  const Dataset d = Simulate(BuiltinWorld("office-boxes"), sim);
  std::vector<StampedPose> odometry;
  for (const LaserScan& s : d.scans) odometry.push_back({s.timestamp, s.odometry});

  for (const LocalFitness fitness : {LocalFitness::kEval1, LocalFitness::kEval2}) {
    LocalSearchParams params;
    params.fitness = fitness;
    HitCountGrid map = EmptyMapFor(d, params);
    const LocalSearchResult r = RunLocalSearch(d, params, 1, map);
    ASSERT_EQ(r.trajectory.size(), d.scans.size());
    EXPECT_EQ(r.evaluations, (d.scans.size() - 1) * 10 * 31);
    const double odometry_ate = Ate(odometry, d), local_ate = Ate(r.trajectory, d);
    EXPECT_LT(local_ate, 0.5 * odometry_ate) << LocalFitnessName(fitness) << ": odometry "
                                             << odometry_ate << " m, local " << local_ate << " m";
    // Every scan is in the map.
    std::size_t returns = 0;
    for (const LaserScan& s : d.scans) {
      for (std::size_t i = 0; i < s.size(); ++i) returns += s.is_return(i);
    }
    EXPECT_EQ(map.total(), returns);
  }
}

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
