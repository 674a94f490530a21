#include "common/optim/differential_evolution.h"

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

class DeStrategyTest : public ::testing::TestWithParam<std::string> {};

TEST_P(DeStrategyTest, ConvergesOnShiftedSphere) {
  const auto problem = ShiftedSphere(2);
  DeParams params;
  params.strategy = ParseDeStrategy(GetParam());
  params.population = 20;
  DifferentialEvolution de(params);
  const OptimResult r = RunFor(problem, de, 60, 3);
  EXPECT_LT(r.best_fitness, 1e-4) << GetParam();
  EXPECT_NEAR(r.best(0), 1.7, 1e-2);
  EXPECT_NEAR(r.best(1), 1.7, 1e-2);
  EXPECT_EQ(r.evaluations, 20u * 61u);
  EXPECT_EQ(r.generations, 60u);
}

INSTANTIATE_TEST_SUITE_P(AllTen, DeStrategyTest, ::testing::ValuesIn(DeStrategyNames()));

TEST(DifferentialEvolutionTest, SolvesRosenbrock) {
  DeParams params;
  params.strategy = DeStrategy::kRand1Bin;
  params.population = 30;
  params.f = 0.7;
  DifferentialEvolution de(params);
  const OptimResult r = RunFor(Rosenbrock2(), de, 300, 1);
  EXPECT_NEAR(r.best(0), 1.0, 1e-3);
  EXPECT_NEAR(r.best(1), 1.0, 2e-3);
}

TEST(DifferentialEvolutionTest, SolvesRastriginIn10Dimensions) {
  // Rastrigin's local minima sit one unit apart; a broken crossover or mutation stalls on one.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  DeParams params;
  params.strategy = DeStrategy::kRand1Bin;
  params.population = 50;
  params.f = 0.5;
  params.cr = 0.1;
  DifferentialEvolution de(params);
  const OptimResult r = RunFor(problem, de, 1000, 4);
  EXPECT_LT(r.best_fitness, 1e-6);
}

TEST(DifferentialEvolutionTest, StaysInsideTheBox) {
  // The optimum lies outside the box, so the search presses against the upper bound.
  const FunctionProblem problem(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  if ((x.array() < 0).any() || (x.array() > 1).any()) return 1e9;
                                  return (x.array() - 3.0).square().sum();
                                });
  DifferentialEvolution de(DeParams{});
  const OptimResult r = RunFor(problem, de, 80, 2);
  EXPECT_LT(r.best_fitness, 1e8);
  EXPECT_NEAR(r.best(0), 1.0, 1e-3);
  EXPECT_NEAR(r.best(1), 1.0, 1e-3);
}

TEST(DifferentialEvolutionTest, RejectsBadParameters) {
  DeParams small;
  small.strategy = DeStrategy::kRand2Exp;
  small.population = 5;
  EXPECT_THROW(DifferentialEvolution{small}, Error);
  DeParams bad_f;
  bad_f.f = 0.0;
  EXPECT_THROW(DifferentialEvolution{bad_f}, Error);
  DeParams bad_cr;
  bad_cr.cr = 1.5;
  EXPECT_THROW(DifferentialEvolution{bad_cr}, Error);
  EXPECT_THROW(ParseDeStrategy("rand3exp"), Error);
}

TEST(DifferentialEvolutionTest, RefusesMultiObjectiveProblems) {
  DifferentialEvolution de(DeParams{});
  Rng rng(1);
  EXPECT_THROW(de.Initialize(ZdtProblem(1, 5), rng), Error);
}

TEST(DifferentialEvolutionTest, StrategyNamesRoundTrip) {
  for (const auto& name : DeStrategyNames()) EXPECT_EQ(DeStrategyName(ParseDeStrategy(name)), name);
  EXPECT_EQ(DeStrategyNames().size(), 10u);
}

TEST(DifferentialEvolutionTest, ResumedRunMatchesUninterrupted) {
  ExpectResumeMatchesUninterrupted(
      Rosenbrock2(), [] { return std::make_unique<DifferentialEvolution>(DeParams{}); }, 7, 20, 9);
}

TEST(DifferentialEvolutionTest, DifferentSeedsExploreDifferently) {
  const auto problem = Rosenbrock2();
  DifferentialEvolution a(DeParams{}), b(DeParams{});
  EXPECT_NE(RunFor(problem, a, 3, 1).best, RunFor(problem, b, 3, 2).best);
}

TEST(DifferentialEvolutionTest, IntegerProblemsGetIntegers) {
  class IntegerSphere : public Problem {
   public:
    const Eigen::VectorXd& lower() const override { return lo_; }
    const Eigen::VectorXd& upper() const override { return hi_; }
    Encoding encoding() const override { return Encoding::kInteger; }
    void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& c, std::span<double> f) const override {
      for (Eigen::Index i = 0; i < c.cols(); ++i) {
        for (Eigen::Index j = 0; j < c.rows(); ++j) EXPECT_EQ(c(j, i), std::round(c(j, i)));
        f[static_cast<std::size_t>(i)] = (c.col(i).array() - 3.0).square().sum();
      }
    }

   private:
    Eigen::VectorXd lo_ = Eigen::VectorXd::Constant(4, -20.0);
    Eigen::VectorXd hi_ = Eigen::VectorXd::Constant(4, 20.0);
  };
  DifferentialEvolution de(DeParams{});
  const OptimResult r = RunFor(IntegerSphere(), de, 60, 5);
  EXPECT_EQ(r.best_fitness, 0.0);
}

}  // namespace
}  // namespace evoslam
