#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "common/optim/differential_evolution.h"
#include "common/optim/exhaustive_search.h"
#include "common/optim/particle_swarm.h"
#include "common/optim/test_problems.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Sphere centred off the box centre, so that an optimiser that only samples the middle fails.
FunctionProblem ShiftedSphere(int dim) {
  return FunctionProblem(
      Eigen::VectorXd::Constant(dim, -5.0), Eigen::VectorXd::Constant(dim, 5.0),
      [](const Eigen::Ref<const Eigen::VectorXd>& x) { return (x.array() - 1.7).square().sum(); });
}

FunctionProblem Rosenbrock2() {
  return FunctionProblem(Eigen::Vector2d(-2, -1), Eigen::Vector2d(2, 3),
                         [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                           return 100 * std::pow(x(1) - x(0) * x(0), 2) + std::pow(1 - x(0), 2);
                         });
}

class DeStrategyTest : public ::testing::TestWithParam<std::string> {};

TEST_P(DeStrategyTest, ConvergesOnShiftedSphere) {
  const auto problem = ShiftedSphere(2);
  DeParams params;
  params.strategy = ParseDeStrategy(GetParam());
  params.population = 20;
  params.generations = 60;
  Rng rng(3);
  const OptimResult r = RunDifferentialEvolution(problem, params, rng);
  EXPECT_LT(r.best_fitness, 1e-4) << GetParam();
  EXPECT_NEAR(r.best(0), 1.7, 1e-2);
  EXPECT_NEAR(r.best(1), 1.7, 1e-2);
  EXPECT_EQ(r.evaluations, 20u * 61u);
  EXPECT_EQ(r.generations, 60u);
}

INSTANTIATE_TEST_SUITE_P(AllTen, DeStrategyTest, ::testing::ValuesIn(DeStrategyNames()));

TEST(DifferentialEvolutionTest, SolvesRosenbrock) {
  const auto problem = Rosenbrock2();
  DeParams params;
  params.strategy = DeStrategy::kRand1Bin;
  params.population = 30;
  params.generations = 300;
  params.f = 0.7;
  Rng rng(1);
  const OptimResult r = RunDifferentialEvolution(problem, params, rng);
  EXPECT_NEAR(r.best(0), 1.0, 1e-3);
  EXPECT_NEAR(r.best(1), 1.0, 2e-3);
}

TEST(DifferentialEvolutionTest, StaysInsideTheBox) {
  // The optimum lies outside the box, so the search presses against the upper bound.
  const FunctionProblem problem(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  if ((x.array() < 0).any() || (x.array() > 1).any()) return 1e9;
                                  return (x.array() - 3.0).square().sum();
                                });
  DeParams params;
  params.generations = 80;
  Rng rng(2);
  const OptimResult r = RunDifferentialEvolution(problem, params, rng);
  EXPECT_LT(r.best_fitness, 1e8);
  EXPECT_NEAR(r.best(0), 1.0, 1e-3);
  EXPECT_NEAR(r.best(1), 1.0, 1e-3);
}

TEST(DifferentialEvolutionTest, RejectsBadParameters) {
  const auto problem = ShiftedSphere(2);
  Rng rng(1);
  DeParams small;
  small.strategy = DeStrategy::kRand2Exp;
  small.population = 5;
  EXPECT_THROW(RunDifferentialEvolution(problem, small, rng), Error);
  DeParams bad_f;
  bad_f.f = 0.0;
  EXPECT_THROW(RunDifferentialEvolution(problem, bad_f, rng), Error);
  DeParams bad_cr;
  bad_cr.cr = 1.5;
  EXPECT_THROW(RunDifferentialEvolution(problem, bad_cr, rng), Error);
  EXPECT_THROW(ParseDeStrategy("rand3exp"), Error);
}

TEST(DifferentialEvolutionTest, StrategyNamesRoundTrip) {
  for (const auto& name : DeStrategyNames()) EXPECT_EQ(DeStrategyName(ParseDeStrategy(name)), name);
  EXPECT_EQ(DeStrategyNames().size(), 10u);
}

template <typename Run>
void ExpectSameBitsWithOneAndTwoThreads(Run run) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const OptimResult one = run();
  omp_set_num_threads(2);
  const OptimResult two = run();
  omp_set_num_threads(saved);
  EXPECT_EQ(one.best_fitness, two.best_fitness);
  EXPECT_EQ(one.best, two.best);
}

TEST(DifferentialEvolutionTest, ResultIndependentOfThreadCount) {
  const auto problem = Rosenbrock2();
  ExpectSameBitsWithOneAndTwoThreads([&] {
    Rng rng(77);
    return RunDifferentialEvolution(problem, DeParams{}, rng);
  });
}

TEST(DifferentialEvolutionTest, DifferentSeedsExploreDifferently) {
  const auto problem = Rosenbrock2();
  Rng a(1), b(2);
  DeParams params;
  params.generations = 3;
  EXPECT_NE(RunDifferentialEvolution(problem, params, a).best,
            RunDifferentialEvolution(problem, params, b).best);
}

TEST(ParticleSwarmTest, ConvergesOnShiftedSphere) {
  const auto problem = ShiftedSphere(3);
  PsoParams params;
  params.particles = 30;
  params.generations = 150;
  Rng rng(4);
  const OptimResult r = RunParticleSwarm(problem, params, rng);
  EXPECT_LT(r.best_fitness, 1e-6);
  EXPECT_EQ(r.evaluations, 30u * 151u);
}

TEST(ParticleSwarmTest, SolvesRosenbrock) {
  const auto problem = Rosenbrock2();
  PsoParams params;
  params.particles = 30;
  params.generations = 400;
  Rng rng(8);
  const OptimResult r = RunParticleSwarm(problem, params, rng);
  EXPECT_NEAR(r.best(0), 1.0, 1e-2);
  EXPECT_NEAR(r.best(1), 1.0, 2e-2);
}

TEST(ParticleSwarmTest, ResultIndependentOfThreadCount) {
  const auto problem = Rosenbrock2();
  ExpectSameBitsWithOneAndTwoThreads([&] {
    Rng rng(5);
    return RunParticleSwarm(problem, PsoParams{}, rng);
  });
}

TEST(ExhaustiveSearchTest, FindsLatticeMinimumIncludingUpperBound) {
  const FunctionProblem problem(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  return std::abs(x(0) - 1.0) + std::abs(x(1) - 0.3);
                                });
  const OptimResult r = RunExhaustiveSearch(problem, Eigen::Vector2d(0.1, 0.1));
  EXPECT_EQ(r.evaluations, 121u);
  EXPECT_NEAR(r.best(0), 1.0, 1e-12);
  EXPECT_NEAR(r.best(1), 0.3, 1e-12);
}

TEST(ExhaustiveSearchTest, ZeroStepUsesCentreAndLargeLatticesAreBatched) {
  const FunctionProblem problem(Eigen::Vector3d(-1, -1, 2), Eigen::Vector3d(1, 1, 4),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  return std::pow(x(0) - 0.25, 2) + std::pow(x(1) + 0.5, 2) + x(2);
                                });
  const OptimResult r = RunExhaustiveSearch(problem, Eigen::Vector3d(0.01, 0.01, 0.0));
  EXPECT_EQ(r.evaluations, 201u * 201u);
  EXPECT_GT(r.generations, 1u);
  EXPECT_NEAR(r.best(0), 0.25, 1e-9);
  EXPECT_NEAR(r.best(1), -0.5, 1e-9);
  EXPECT_DOUBLE_EQ(r.best(2), 3.0);
}

}  // namespace
}  // namespace evoslam
