#include "common/optim/particle_swarm.h"

#include <gtest/gtest.h>

#include <memory>

#include "common/optim/optim_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::ExpectResumeMatchesUninterrupted;
using testing::Rosenbrock2;
using testing::RunFor;
using testing::ShiftedSphere;

class PsoNeighbourhoodTest : public ::testing::TestWithParam<PsoNeighbourhood> {};

TEST_P(PsoNeighbourhoodTest, ConvergesOnShiftedSphere) {
  PsoParams params;
  params.particles = 30;
  params.neighbourhood = GetParam();
  ParticleSwarm pso(params);
  const OptimResult r = RunFor(ShiftedSphere(3), pso, 200, 4);
  EXPECT_LT(r.best_fitness, 1e-6);
  EXPECT_EQ(r.evaluations, 30u * 201u);
}

TEST_P(PsoNeighbourhoodTest, SolvesRosenbrock) {
  PsoParams params;
  params.particles = 30;
  params.neighbourhood = GetParam();
  ParticleSwarm pso(params);
  const OptimResult r = RunFor(Rosenbrock2(), pso, 400, 8);
  EXPECT_NEAR(r.best(0), 1.0, 1e-2);
  EXPECT_NEAR(r.best(1), 1.0, 2e-2);
}

TEST_P(PsoNeighbourhoodTest, FindsLowBasinsOfRastrigin) {
  // Random sampling of the same 20 040 points ends near 60 in 10-D; both neighbourhoods end a
  // few basins from the optimum (mean of five seeds about 6 when measured).
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  double total = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    PsoParams params;
    params.particles = 40;
    params.neighbourhood = GetParam();
    ParticleSwarm pso(params);
    total += RunFor(problem, pso, 500, seed).best_fitness;
  }
  EXPECT_LT(total / 5, 10.0);
}

TEST_P(PsoNeighbourhoodTest, ResumedRunMatchesUninterrupted) {
  PsoParams params;
  params.neighbourhood = GetParam();
  ExpectResumeMatchesUninterrupted(
      Rosenbrock2(), [&] { return std::make_unique<ParticleSwarm>(params); }, 5, 15, 3);
}

INSTANTIATE_TEST_SUITE_P(Both, PsoNeighbourhoodTest,
                         ::testing::Values(PsoNeighbourhood::kGlobal, PsoNeighbourhood::kRing));

TEST(ParticleSwarmTest, RingKeepsMoreDiversityThanGlobalBest) {
  // On Rastrigin the global-best swarm collapses onto one basin sooner: after the same number of
  // generations its personal bests are spread over a smaller region.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  const auto spread = [&](PsoNeighbourhood n) {
    double total = 0.0;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      PsoParams params;
      params.particles = 40;
      params.neighbourhood = n;
      ParticleSwarm pso(params);
      RunFor(problem, pso, 60, seed);
      const Eigen::MatrixXd& x = pso.population().x;
      const Eigen::VectorXd mean = x.rowwise().mean();
      total += (x.colwise() - mean).norm();
    }
    return total;
  };
  EXPECT_GT(spread(PsoNeighbourhood::kRing), 1.5 * spread(PsoNeighbourhood::kGlobal));
}

TEST(ParticleSwarmTest, RejectsBadParameters) {
  PsoParams one;
  one.particles = 1;
  EXPECT_THROW(ParticleSwarm{one}, Error);
  PsoParams frozen;
  frozen.vmax_fraction = 0.0;
  EXPECT_THROW(ParticleSwarm{frozen}, Error);
  EXPECT_THROW(ParsePsoNeighbourhood("star"), Error);
  EXPECT_EQ(ParsePsoNeighbourhood(PsoNeighbourhoodName(PsoNeighbourhood::kRing)),
            PsoNeighbourhood::kRing);
}

TEST(ParticleSwarmTest, RestoreRefusesMissingMemory) {
  ParticleSwarm pso(PsoParams{});
  Rng rng(1);
  pso.Initialize(Rosenbrock2(), rng);
  AlgorithmState state = pso.Save();
  state.memory.erase("velocity");
  ParticleSwarm other(PsoParams{});
  EXPECT_THROW(other.Restore(state), Error);
}

}  // namespace
}  // namespace evoslam
