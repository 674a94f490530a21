#include "common/optim/simple_ga.h"

#include <gtest/gtest.h>

#include <memory>

#include "common/optim/ga_operators.h"
#include "common/optim/ga_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::BestFitnesses;
using testing::ExpectResumeMatchesUninterrupted;
using testing::Mean;
using testing::Rosenbrock2;
using testing::RunFor;
using testing::RunsBelow;
using testing::RunsFindingTheWindowMinimum;
using testing::WindowParams;

TEST(SimpleGaTest, ConvergesOnSphere) {
  // The box is 10.24 wide; a random search with the same budget ends near f = 0.4.
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  for (const double best : BestFitnesses<SimpleGa>(problem, GaParams{}, 100, 5))
    EXPECT_LT(best, 0.05);
}

TEST(SimpleGaTest, UniformCrossoverConvergesToo) {
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  GaParams params;
  params.crossover = GaCrossover::kUniform;
  for (const double best : BestFitnesses<SimpleGa>(problem, params, 100, 5)) EXPECT_LT(best, 0.05);
}

TEST(SimpleGaTest, CountsOneBatchOfNewCandidatesPerGeneration) {
  SimpleGa ga(GaParams{});
  const OptimResult r = RunFor(TestFunctionProblem(TestFunction::kSphere, 2), ga, 30, 1);
  EXPECT_EQ(r.generations, 30u);
  EXPECT_EQ(r.evaluations, 20u + 30u * 12u);
}

TEST(SimpleGaTest, WithoutMutationItStallsOnSphere) {
  // Elitist mutation is what refines the best individual; without it the mating pool soon holds
  // copies of one chromosome and crossover has nothing left to mix.
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  GaParams no_mutation;
  no_mutation.mutants = 0;
  no_mutation.pairs = 6;  // the same number of evaluations
  const double with = Mean(BestFitnesses<SimpleGa>(problem, GaParams{}, 100, 5));
  const double without = Mean(BestFitnesses<SimpleGa>(problem, no_mutation, 100, 5));
  EXPECT_GT(without, 10.0 * with);
}

TEST(SimpleGaTest, CrossoverHelpsOnRastrigin) {
  // Mutants alone only search around the best individual; crossover recombines coordinates of
  // different basins, which a multimodal separable function rewards.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  GaParams no_crossover;
  no_crossover.pairs = 0;
  no_crossover.mutants = 12;  // the same number of evaluations
  const double with = Mean(BestFitnesses<SimpleGa>(problem, GaParams{}, 100, 10));
  const double without = Mean(BestFitnesses<SimpleGa>(problem, no_crossover, 100, 10));
  EXPECT_LT(with, 0.9 * without);
}

TEST(SimpleGaTest, ReachesTheRosenbrockMinimumInMostRuns) {
  // The SGA converges early and some runs stall in the curved valley; most reach its floor.
  const TestFunctionProblem problem(TestFunction::kRosenbrock, 2);
  GaParams no_mutation;
  no_mutation.mutants = 0;
  no_mutation.pairs = 6;
  EXPECT_GE(RunsBelow(BestFitnesses<SimpleGa>(problem, GaParams{}, 400, 20), 0.1), 9);
  EXPECT_LE(RunsBelow(BestFitnesses<SimpleGa>(problem, no_mutation, 400, 20), 0.1), 6);
}

TEST(SimpleGaTest, FindsTheLocalizationMinimumOnTheGrid) {
  EXPECT_GE(RunsFindingTheWindowMinimum<SimpleGa>(WindowParams(), 50, 10), 9);
}

TEST(SimpleGaTest, ReplacesOnlyTheWorstAndKeepsTheBest) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 4);
  SimpleGa ga(GaParams{});
  Rng rng(21);
  ga.Initialize(problem, rng);
  for (int g = 0; g < 20; ++g) {
    const Population before = ga.population();
    const std::vector<std::size_t> ranking = RankByFitness(before.f);
    ga.Step(problem, rng);
    const Population& after = ga.population();
    // The 12 best stay where they were; the 8 worst may change.
    for (std::size_t k = 0; k < 12; ++k) {
      const auto i = static_cast<Eigen::Index>(ranking[k]);
      EXPECT_EQ(after.x.col(i), before.x.col(i));
    }
    EXPECT_LE(after.f(0, static_cast<Eigen::Index>(after.BestIndex())),
              before.f(0, static_cast<Eigen::Index>(before.BestIndex())));
  }
}

TEST(SimpleGaTest, PopulationIsItsDecodedChromosomes) {
  const TestFunctionProblem problem(TestFunction::kRosenbrock, 3);
  SimpleGa ga(GaParams{});
  RunFor(problem, ga, 10, 4);
  const BinaryCoding coding(problem.lower(), problem.upper(), 16, 0.0);
  Eigen::MatrixXd decoded;
  DecodeCandidates(problem, coding, ga.chromosomes(), decoded);
  EXPECT_EQ(decoded, ga.population().x);
}

TEST(SimpleGaTest, ImmigrantsAreEncodedOnTheGrid) {
  const testing::GridWindowProblem problem;
  SimpleGa ga(WindowParams());
  Rng rng(2);
  ga.Initialize(problem, rng);
  const Eigen::Vector2d x(0.1234, -0.2871);
  ga.Replace(3, x, Eigen::VectorXd::Constant(1, -1.0));
  EXPECT_EQ(ga.population().x.col(3), x);
  const BinaryCoding coding(problem.lower(), problem.upper(), 16, 0.01);
  Eigen::Vector2d decoded;
  coding.Decode(ga.chromosomes().col(3), decoded);
  EXPECT_NEAR(decoded(0), 0.12, 1e-12);
  EXPECT_NEAR(decoded(1), -0.29, 1e-12);
}

TEST(SimpleGaTest, IntegerProblemsGetIntegers) {
  class IntegerSphere : public Problem {
   public:
    const Eigen::VectorXd& lower() const override { return sphere_.lower(); }
    const Eigen::VectorXd& upper() const override { return sphere_.upper(); }
    Encoding encoding() const override { return Encoding::kInteger; }
    void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& c, std::span<double> f) const override {
      EXPECT_EQ(c, c.array().round().matrix());
      sphere_.Evaluate(c, f);
    }

   private:
    TestFunctionProblem sphere_{TestFunction::kSphere, 4};
  };
  SimpleGa ga(GaParams{});
  EXPECT_EQ(RunFor(IntegerSphere(), ga, 60, 5).best_fitness, 0.0);
}

TEST(SimpleGaTest, ResumedRunMatchesUninterrupted) {
  for (const GaCrossover crossover : {GaCrossover::kTwoPoint, GaCrossover::kUniform}) {
    GaParams params = WindowParams();
    params.crossover = crossover;
    ExpectResumeMatchesUninterrupted(
        testing::GridWindowProblem(), [&] { return std::make_unique<SimpleGa>(params); }, 6, 20,
        17);
  }
}

TEST(SimpleGaTest, RestoreRefusesBadMemory) {
  SimpleGa ga(GaParams{});
  Rng rng(1);
  ga.Initialize(Rosenbrock2(), rng);
  AlgorithmState missing = ga.Save();
  missing.memory.erase("chromosomes");
  AlgorithmState not_a_code = ga.Save();
  not_a_code.memory["chromosomes"](1, 4) = 0.5;
  AlgorithmState no_box = ga.Save();
  no_box.memory.erase("box");
  SimpleGa other(GaParams{});
  EXPECT_THROW(other.Restore(missing), Error);
  EXPECT_THROW(other.Restore(not_a_code), Error);
  EXPECT_THROW(other.Restore(no_box), Error);
  EXPECT_NO_THROW(other.Restore(ga.Save()));
}

TEST(SimpleGaTest, RejectsBadParameters) {
  const auto with = [](auto change) {
    GaParams params;
    change(params);
    return params;
  };
  EXPECT_NO_THROW(SimpleGa(GaParams{}));
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.bits = 0; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.bits = 31; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.grid_step = -0.01; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.elite_fraction = 0.0; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.elite_fraction = 1.5; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.elite_fraction = 0.05; })), Error);  // pool of 1
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.mutation_box = 0.0; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.replaced = 0; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.replaced = 20; })), Error);
  EXPECT_THROW(SimpleGa(with([](GaParams& p) {
                 p.mutants = 0;
                 p.pairs = 3;
               })),
               Error);  // 6 < 8
  EXPECT_NO_THROW(SimpleGa(with([](GaParams& p) {
    p.mutants = 0;
    p.pairs = 4;
  })));
  EXPECT_THROW(SimpleGa(with([](GaParams& p) { p.population = 2; })), Error);
}

TEST(SimpleGaTest, CrossoverNamesRoundTrip) {
  for (const GaCrossover c : {GaCrossover::kTwoPoint, GaCrossover::kUniform})
    EXPECT_EQ(ParseGaCrossover(GaCrossoverName(c)), c);
  EXPECT_EQ(GaCrossoverName(GaCrossover::kTwoPoint), "two-point");
  EXPECT_THROW(ParseGaCrossover("one-point"), Error);
}

TEST(SimpleGaTest, RefusesMultiObjectiveProblems) {
  SimpleGa ga(GaParams{});
  Rng rng(1);
  EXPECT_THROW(ga.Initialize(ZdtProblem(1, 5), rng), Error);
}

TEST(SimpleGaTest, BitFlipsHelpOnManyCoordinates) {
  // With 003's operators alone, crossover of 20 individuals soon has no new bits to offer in 10
  // dimensions; about one flipped bit per child keeps the search moving.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  double plain = 0.0, flipped = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    GaParams params;
    SimpleGa without(params);
    plain += RunFor(problem, without, 2000, seed).best_fitness;
    params.bit_flip = 1.0 / 160;
    SimpleGa with(params);
    flipped += RunFor(problem, with, 2000, seed).best_fitness;
  }
  EXPECT_LT(flipped, 0.5 * plain);
}

}  // namespace
}  // namespace evoslam
