#include "common/optim/diploid_ga.h"

#include <gtest/gtest.h>

#include <memory>

#include "common/optim/ga_operators.h"
#include "common/optim/ga_testing.h"
#include "common/optim/simple_ga.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::BestFitnesses;
using testing::ExpectResumeMatchesUninterrupted;
using testing::Mean;
using testing::MeanSpread;
using testing::Rosenbrock2;
using testing::RunFor;
using testing::RunsBelow;
using testing::RunsFindingTheWindowMinimum;
using testing::WindowParams;

TEST(AdaptiveGaTest, ConvergesOnSphere) {
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  for (const double best : BestFitnesses<AdaptiveGa>(problem, GaParams{}, 100, 5))
    EXPECT_LT(best, 0.05);
}

TEST(AdaptiveGaTest, CostsWhatTheSimpleGaCosts) {
  // Only the expressed chromosome is evaluated.
  const TestFunctionProblem problem(TestFunction::kSphere, 2);
  AdaptiveGa aga(GaParams{});
  SimpleGa sga(GaParams{});
  EXPECT_EQ(RunFor(problem, aga, 30, 1).evaluations, 20u + 30u * 12u);
  EXPECT_EQ(RunFor(problem, sga, 30, 1).evaluations, 20u + 30u * 12u);
}

TEST(AdaptiveGaTest, ReachesTheRosenbrockMinimumInMostRuns) {
  const TestFunctionProblem problem(TestFunction::kRosenbrock, 2);
  EXPECT_GE(RunsBelow(BestFitnesses<AdaptiveGa>(problem, GaParams{}, 400, 20), 0.1), 9);
}

TEST(AdaptiveGaTest, CrossoverHelpsOnRastrigin) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  GaParams no_crossover;
  no_crossover.pairs = 0;
  no_crossover.mutants = 12;
  const double with = Mean(BestFitnesses<AdaptiveGa>(problem, GaParams{}, 100, 10));
  const double without = Mean(BestFitnesses<AdaptiveGa>(problem, no_crossover, 100, 10));
  EXPECT_LT(with, 0.85 * without);
}

TEST(AdaptiveGaTest, KeepsMoreDiversityThanTheSimpleGa) {
  // The SGA's population collapses onto one Rastrigin basin within a few dozen generations; the
  // aGA's dormant chromosomes keep feeding other basins' bits into its children.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 5);
  const double aga = MeanSpread<AdaptiveGa>(problem, GaParams{}, 100, 5);
  const double sga = MeanSpread<SimpleGa>(problem, GaParams{}, 100, 5);
  EXPECT_GT(aga, 0.25);  // a quarter of the distance between neighbouring basins
  EXPECT_GT(aga, 10.0 * sga);
}

TEST(AdaptiveGaTest, DiversityCostsNothingOnRastrigin) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  const double aga = Mean(BestFitnesses<AdaptiveGa>(problem, GaParams{}, 100, 10));
  const double sga = Mean(BestFitnesses<SimpleGa>(problem, GaParams{}, 100, 10));
  EXPECT_LT(aga, 1.1 * sga);
}

TEST(AdaptiveGaTest, FindsTheLocalizationMinimumOnTheGrid) {
  EXPECT_GE(RunsFindingTheWindowMinimum<AdaptiveGa>(WindowParams(), 50, 10), 9);
}

// Whether `pair` (expressed, dormant) could come from crossing a's expressed chromosome with b's
// dormant one: the two strings hold the same bits between them.
bool SharesOutBits(const Chromosome& expressed, const Chromosome& dormant, const Chromosome& a,
                   const Chromosome& b) {
  for (Eigen::Index j = 0; j < a.size(); ++j) {
    if ((expressed(j) & dormant(j)) != (a(j) & b(j)) ||
        (expressed(j) ^ dormant(j)) != (a(j) ^ b(j)))
      return false;
  }
  return true;
}

TEST(AdaptiveGaTest, NewcomersAreChildrenOfTheMatingPoolOrMutantsNearTheBest) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 3);
  const GaParams params;
  AdaptiveGa aga(params);
  Rng rng(12);
  aga.Initialize(problem, rng);
  const auto half = static_cast<std::int64_t>(std::llround(params.mutation_box * 65535));
  int children = 0;
  int mutants = 0;
  for (int g = 0; g < 10; ++g) {
    const Chromosomes expressed = aga.chromosomes();
    const Chromosomes dormant = aga.dormant();
    const std::vector<std::size_t> ranking = RankByFitness(aga.population().f);
    aga.Step(problem, rng);
    for (std::size_t k = 0; k < params.replaced; ++k) {
      const auto i = static_cast<Eigen::Index>(ranking[ranking.size() - 1 - k]);
      const Chromosome e = aga.chromosomes().col(i);
      const Chromosome d = aga.dormant().col(i);
      bool child = false;
      for (std::size_t p = 0; p < MatingPoolSize(params) && !child; ++p) {
        for (std::size_t q = 0; q < MatingPoolSize(params) && !child; ++q) {
          child =
              p != q && SharesOutBits(e, d, expressed.col(static_cast<Eigen::Index>(ranking[p])),
                                      dormant.col(static_cast<Eigen::Index>(ranking[q])));
        }
      }
      bool mutant = false;
      for (Eigen::Index r = 0; r < dormant.cols() && !mutant; ++r) mutant = d == dormant.col(r);
      const Chromosome best = expressed.col(static_cast<Eigen::Index>(ranking[0]));
      for (Eigen::Index j = 0; j < 3; ++j) {
        mutant = mutant && std::abs(static_cast<std::int64_t>(e(j)) -
                                    static_cast<std::int64_t>(best(j))) <= half;
      }
      EXPECT_TRUE(child || mutant) << "generation " << g << ", individual " << i;
      children += child;
      mutants += mutant && !child;
    }
  }
  EXPECT_GT(children, 0);
  EXPECT_GT(mutants, 0);
}

TEST(AdaptiveGaTest, ImmigrantsReplaceOnlyTheExpressedChromosome) {
  const testing::GridWindowProblem problem;
  AdaptiveGa aga(WindowParams());
  Rng rng(2);
  aga.Initialize(problem, rng);
  const Chromosome dormant = aga.dormant().col(5);
  const Eigen::Vector2d x(-0.05, 0.21);
  aga.Replace(5, x, Eigen::VectorXd::Constant(1, -1.0));
  EXPECT_EQ(aga.dormant().col(5), dormant);
  const BinaryCoding coding(problem.lower(), problem.upper(), 16, 0.01);
  EXPECT_EQ(aga.chromosomes().col(5), coding.Encode(x));
}

TEST(AdaptiveGaTest, ResumedRunMatchesUninterrupted) {
  // Children read the dormant chromosomes, so a resume that lost them would part ways.
  for (const GaCrossover crossover : {GaCrossover::kTwoPoint, GaCrossover::kUniform}) {
    GaParams params = WindowParams();
    params.crossover = crossover;
    ExpectResumeMatchesUninterrupted(
        testing::GridWindowProblem(), [&] { return std::make_unique<AdaptiveGa>(params); }, 6, 20,
        17);
  }
}

TEST(AdaptiveGaTest, RestoreRefusesMissingDormantChromosomes) {
  AdaptiveGa aga(GaParams{});
  Rng rng(1);
  aga.Initialize(Rosenbrock2(), rng);
  AlgorithmState state = aga.Save();
  state.memory.erase("dormant");
  AdaptiveGa other(GaParams{});
  EXPECT_THROW(other.Restore(state), Error);
  other.Restore(aga.Save());
  EXPECT_EQ(other.dormant(), aga.dormant());
}

TEST(AdaptiveGaTest, RejectsBadParameters) {
  GaParams params;
  params.replaced = params.population;
  EXPECT_THROW(AdaptiveGa{params}, Error);
  EXPECT_EQ(AdaptiveGa(GaParams{}).name(), "aga");
}

}  // namespace
}  // namespace evoslam
