#include "common/optim/mu_plus_lambda.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "common/optim/optim_testing.h"
#include "common/optim/pareto.h"
#include "common/optim/stop_criteria.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::ExpectResumeMatchesUninterrupted;
using testing::ExpectSameBitsWithOneAndTwoThreads;
using testing::ExpectSamePopulationWithOneAndTwoThreads;
using testing::RecordingProblem;
using testing::Rosenbrock2;
using testing::RunFor;
using testing::RunGenerations;

// Settings for a problem that is not a 002 chromosome: every gene is its own column.
MuPlusLambdaParams Generic() {
  MuPlusLambdaParams params;
  params.gene_group = 1;
  params.column = 1;
  params.variance_threshold = 0.0;
  return params;
}

// Starts `ea` from the given parents (columns of x) at generation `generation`.
void StartFrom(MuPlusLambdaEa& ea, const Problem& problem, const Eigen::MatrixXd& x,
               std::size_t generation) {
  AlgorithmState state;
  state.population.x = x;
  EvaluateBatch(problem, x, state.population.f);
  state.generation = generation;
  ea.Restore(state);
}

// A box [lo, hi]^dim whose fitness is the first coordinate; only the candidates matter.
FunctionProblem Box(int dim, double lo, double hi) {
  return FunctionProblem(Eigen::VectorXd::Constant(dim, lo), Eigen::VectorXd::Constant(dim, hi),
                         [](const Eigen::Ref<const Eigen::VectorXd>& x) { return x(0); });
}

// Parent p has every gene equal to `scale` * p + `offset`, so that a gene names its parent.
Eigen::MatrixXd LabelledParents(int dim, int mu, double scale, double offset) {
  Eigen::MatrixXd x(dim, mu);
  for (int p = 0; p < mu; ++p) x.col(p).setConstant(scale * p + offset);
  return x;
}

Eigen::MatrixXd FirstFrontOf(const Eigen::MatrixXd& f) {
  const std::vector<std::size_t> front = FirstFront(f);
  Eigen::MatrixXd out(f.rows(), static_cast<Eigen::Index>(front.size()));
  for (std::size_t i = 0; i < front.size(); ++i)
    out.col(static_cast<Eigen::Index>(i)) = f.col(static_cast<Eigen::Index>(front[i]));
  return out;
}

TEST(MuPlusLambdaTest, SolvesSphere) {
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  MuPlusLambdaParams params = Generic();
  params.pm = 0.3;
  MuPlusLambdaEa ea(params);
  const OptimResult r = RunFor(problem, ea, 200, 1);
  EXPECT_LT(r.best_fitness, 1e-4);
  EXPECT_EQ(r.evaluations, 10u + 70u * 200u);
}

TEST(MuPlusLambdaTest, SolvesRosenbrock) {
  MuPlusLambdaParams params = Generic();
  params.pm = 0.5;
  params.generation_limit = 200;
  MuPlusLambdaEa ea(params);
  const OptimResult r = RunFor(Rosenbrock2(), ea, 200, 2);
  EXPECT_LT(r.best_fitness, 1e-3);
  EXPECT_NEAR(r.best(0), 1.0, 0.05);
  EXPECT_NEAR(r.best(1), 1.0, 0.1);
}

TEST(MuPlusLambdaTest, SolvesRastrigin) {
  // Rastrigin's basins are one unit apart: a step of up to c * 5.12 = 1 can cross them, and
  // only working selection keeps the jumps that land in a better basin.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 3);
  MuPlusLambdaParams params = Generic();
  params.pm = 0.3;
  params.c = 0.2;
  params.generation_limit = 300;
  MuPlusLambdaEa ea(params);
  const OptimResult r = RunFor(problem, ea, 300, 3);
  EXPECT_LT(r.best_fitness, 1e-2);
  EXPECT_LT(r.best.cwiseAbs().maxCoeff(), 0.01);
}

class MuPlusLambdaZdtTest : public ::testing::TestWithParam<int> {};

TEST_P(MuPlusLambdaZdtTest, ApproachesTheFrontAcrossItsWidth) {
  const ZdtProblem problem(GetParam(), 10);
  MuPlusLambdaParams params = Generic();
  params.mu = 50;
  params.lambda = 350;
  params.pm = 0.1;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    MuPlusLambdaEa ea(params);
    RunGenerations(problem, ea, 100, seed);
    const Eigen::MatrixXd front = FirstFrontOf(ea.population().f);
    const double igd = InvertedGenerationalDistance(problem, front);
    RecordProperty("igd_seed_" + std::to_string(seed), std::to_string(igd));
    EXPECT_LT(igd, 0.05) << "seed " << seed;
    EXPECT_LT(front.row(0).minCoeff(), 0.05) << "seed " << seed;
    EXPECT_GT(front.row(0).maxCoeff(), 0.85) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(Zdt1And2, MuPlusLambdaZdtTest, ::testing::Values(1, 2));

TEST(MuPlusLambdaTest, RandomSurvivorsDoNotApproachTheFront) {
  // The same run with q = 1 (every tournament a random draw) stays far from the front, so the
  // bound above measures selection, not the problem's ease.
  const ZdtProblem problem(1, 10);
  MuPlusLambdaParams params = Generic();
  params.mu = 50;
  params.lambda = 350;
  params.pm = 0.1;
  params.q = 1;
  MuPlusLambdaEa ea(params);
  RunGenerations(problem, ea, 100, 1);
  const double igd = InvertedGenerationalDistance(problem, FirstFrontOf(ea.population().f));
  RecordProperty("igd", std::to_string(igd));
  EXPECT_GT(igd, 0.5);
}

// Checks the children of one generation from parents labelled 1..mu (LabelledParents): pairs are
// complementary, and returns how many pairs split at least one gene group between the parents.
std::size_t SplitPairs(const Eigen::MatrixXd& children, std::size_t group) {
  std::size_t split = 0;
  for (Eigen::Index k = 0; k + 1 < children.cols(); k += 2) {
    const auto a = children.col(k);
    const auto b = children.col(k + 1);
    const double low = std::min(a.minCoeff(), b.minCoeff());
    const double high = std::max(a.maxCoeff(), b.maxCoeff());
    EXPECT_NE(low, high) << "pair " << k / 2 << " has one parent twice";
    for (Eigen::Index j = 0; j < a.size(); ++j) {
      EXPECT_TRUE(a(j) == low || a(j) == high) << "gene " << j << " of child " << k;
      EXPECT_EQ(a(j) + b(j), low + high)
          << "children " << k << " and " << k + 1 << " are not complementary at gene " << j;
    }
    bool splits = false;
    for (Eigen::Index g = 0; g < a.size(); g += static_cast<Eigen::Index>(group)) {
      for (Eigen::Index j = g + 1; j < g + static_cast<Eigen::Index>(group); ++j)
        splits = splits || a(j) != a(g);
    }
    if (splits) ++split;
  }
  return split;
}

TEST(MuPlusLambdaTest, CrossoverSwitchesFromGenesToGroupsAtHalfTheGenerationLimit) {
  const auto box = Box(12, 0.0, 20.0);
  const RecordingProblem problem(box);
  MuPlusLambdaParams params;  // 002's gene_group 2, column 6, generation_limit 100
  params.pc = 1.0;
  params.pm = 0.0;
  const Eigen::MatrixXd parents = LabelledParents(12, 10, 1.0, 1.0);

  MuPlusLambdaEa first_half(params);
  StartFrom(first_half, problem, parents, 49);
  Rng rng_early(4);
  first_half.Step(problem, rng_early);
  const Eigen::MatrixXd& early = problem.batches().back();
  ASSERT_EQ(early.cols(), 70);
  // Each of the 35 pairs keeps all six pairs of genes together with probability 2^-6 only.
  EXPECT_GT(SplitPairs(early, 2), 25u);

  MuPlusLambdaEa second_half(params);
  StartFrom(second_half, problem, parents, 50);
  Rng rng_late(4);
  second_half.Step(problem, rng_late);
  const Eigen::MatrixXd late = problem.batches().back();
  EXPECT_EQ(SplitPairs(late, 2), 0u);
  // The groups still mix: most children hold genes of both parents.
  std::size_t mixed = 0;
  for (Eigen::Index k = 0; k < late.cols(); ++k)
    mixed += late.col(k).minCoeff() != late.col(k).maxCoeff() ? 1 : 0;
  EXPECT_GT(mixed, 50u);
}

TEST(MuPlusLambdaTest, WithoutCrossoverChildrenCopyDistinctParents) {
  const auto box = Box(4, 0.0, 20.0);
  const RecordingProblem problem(box);
  MuPlusLambdaParams params = Generic();
  params.pc = 0.0;
  params.pm = 0.0;
  MuPlusLambdaEa ea(params);
  StartFrom(ea, problem, LabelledParents(4, 10, 1.0, 1.0), 0);
  Rng rng(6);
  ea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  for (Eigen::Index k = 0; k < children.cols(); k += 2) {
    EXPECT_EQ(children.col(k).minCoeff(), children.col(k).maxCoeff());
    EXPECT_NE(children(0, k), children(0, k + 1));
  }
}

TEST(MuPlusLambdaTest, MutationMovesOneGenePerColumnByAtMostCTimesTheLargestBound) {
  // Bounds [-10, 40]: s = 40, so steps reach c * s = 0.4 (not 0.5 = c * width, nor 0.1).
  const FunctionProblem box(Eigen::VectorXd::Constant(12, -10.0),
                            Eigen::VectorXd::Constant(12, 40.0),
                            [](const Eigen::Ref<const Eigen::VectorXd>& x) { return x(0); });
  const RecordingProblem problem(box);
  MuPlusLambdaParams params;  // columns of 6 genes in groups of 2
  params.pc = 0.0;
  params.pm = 1.0;
  params.c = 0.01;
  params.lambda = 400;
  MuPlusLambdaEa ea(params);
  const Eigen::MatrixXd parents = LabelledParents(12, 10, 3.0, 0.0);
  StartFrom(ea, problem, parents, 0);
  Rng rng(8);
  ea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  double largest = 0.0;
  std::vector<int> hits(12, 0);
  for (Eigen::Index k = 0; k < children.cols(); ++k) {
    const Eigen::VectorXd parent =
        parents.col(static_cast<Eigen::Index>(std::lround(children.col(k).mean() / 3.0)));
    const Eigen::VectorXd step = children.col(k) - parent;
    for (Eigen::Index start : {0, 6}) {
      int changed = 0;
      for (Eigen::Index j = start; j < start + 6; ++j) {
        if (step(j) == 0.0) continue;
        ++changed;
        ++hits[static_cast<std::size_t>(j)];
        EXPECT_LE(std::abs(step(j)), 0.4);
        largest = std::max(largest, std::abs(step(j)));
      }
      EXPECT_EQ(changed, 1) << "child " << k << ", column at " << start;
    }
  }
  EXPECT_GT(largest, 0.38);
  // One group in three, then one gene in two: each gene about 400 / 6 times.
  for (const int h : hits) EXPECT_NEAR(h, 400.0 / 6.0, 25.0);
}

TEST(MuPlusLambdaTest, MutationDropsStepsThatLeaveTheBox) {
  // Parents half a step below the upper bound: a step up by more than that is dropped, not
  // clipped, so no child reaches the bound and about a quarter of the columns stay put.
  const auto box = Box(6, -10.0, 10.0);
  const RecordingProblem problem(box);
  MuPlusLambdaParams params = Generic();
  params.pc = 0.0;
  params.pm = 1.0;
  params.lambda = 400;
  MuPlusLambdaEa ea(params);
  const Eigen::MatrixXd parents = Eigen::MatrixXd::Constant(6, 10, 9.5);
  StartFrom(ea, problem, parents, 0);
  Rng rng(9);
  ea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  EXPECT_LT(children.maxCoeff(), 10.0);
  EXPECT_GE(children.minCoeff(), 8.5);
  const double kept =
      static_cast<double>((children.array() == 9.5).count()) / static_cast<double>(children.size());
  EXPECT_NEAR(kept, 0.25, 0.04);
}

TEST(MuPlusLambdaTest, ShortLastColumnAndGroupAreMutatedToo) {
  // Nine genes in columns of six: [0..5] and [6, 7, 8], the second holding groups {6, 7}, {8}.
  const auto box = Box(9, -10.0, 10.0);
  const RecordingProblem problem(box);
  MuPlusLambdaParams params;
  params.pc = 0.0;
  params.pm = 1.0;
  params.lambda = 800;
  MuPlusLambdaEa ea(params);
  StartFrom(ea, problem, Eigen::MatrixXd::Zero(9, 10), 0);
  Rng rng(10);
  ea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  std::vector<int> hits(9, 0);
  for (Eigen::Index k = 0; k < children.cols(); ++k) {
    EXPECT_EQ((children.col(k).head(6).array() != 0.0).count(), 1);
    EXPECT_EQ((children.col(k).tail(3).array() != 0.0).count(), 1);
    for (Eigen::Index j = 0; j < 9; ++j) hits[static_cast<std::size_t>(j)] += children(j, k) != 0;
  }
  EXPECT_NEAR(hits[6], 200, 40);
  EXPECT_NEAR(hits[7], 200, 40);
  EXPECT_NEAR(hits[8], 400, 45);
}

// Fitness -1000 * (batches evaluated before) + 0.001 * (column in the batch): each generation's
// children beat every earlier candidate, and every candidate has its own fitness.
class ClockProblem : public Problem {
 public:
  const Eigen::VectorXd& lower() const override { return lo_; }
  const Eigen::VectorXd& upper() const override { return hi_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& /*candidates*/,
                std::span<double> fitness) const override {
    const double batch = batches_++;
    for (std::size_t i = 0; i < fitness.size(); ++i)
      fitness[i] = -1000.0 * batch + 0.001 * static_cast<double>(i);
  }

 private:
  Eigen::VectorXd lo_ = Eigen::VectorXd::Zero(3);
  Eigen::VectorXd hi_ = Eigen::VectorXd::Ones(3);
  mutable std::atomic<int> batches_ = 0;
};

TEST(MuPlusLambdaTest, SurvivorsAreEightyPercentOffspringEvenWhenAllOffspringAreBetter) {
  for (const std::size_t mu : {10u, 7u}) {
    const ClockProblem problem;
    MuPlusLambdaParams params = Generic();
    params.mu = mu;
    MuPlusLambdaEa ea(params);
    Rng rng(11);
    ea.Initialize(problem, rng);
    const Eigen::MatrixXd parents = ea.population().x;
    ea.Step(problem, rng);
    const Eigen::MatrixXd& f = ea.population().f;
    const Eigen::Index from_parents = mu == 10 ? 2 : 1;  // 20 % of 10; 7 - round(0.8 * 7)
    EXPECT_EQ((f.array() >= 0.0).count(), from_parents) << mu;
    EXPECT_EQ((f.array() < -999.0).count(), static_cast<Eigen::Index>(mu) - from_parents) << mu;
    const std::set<double> distinct(f.data(), f.data() + f.size());
    EXPECT_EQ(distinct.size(), mu) << "a survivor was drawn twice";
    for (Eigen::Index i = 0; i < f.cols(); ++i) {
      if (f(0, i) < 0.0) continue;
      const auto parent = static_cast<Eigen::Index>(std::lround(f(0, i) / 0.001));
      EXPECT_EQ(ea.population().x.col(i), parents.col(parent));
    }
  }
}

TEST(MuPlusLambdaTest, TournamentsAsLargeAsThePoolsTakeTheBestOfEach) {
  // With q above both pool sizes every tournament sees the whole remaining pool, so survivors are
  // the 8 best children and the 2 best parents, each once.
  const auto sphere = testing::ShiftedSphere(3);
  const RecordingProblem problem(sphere);
  MuPlusLambdaParams params = Generic();
  params.q = 100;
  MuPlusLambdaEa ea(params);
  Rng rng(12);
  ea.Initialize(problem, rng);
  const Eigen::MatrixXd parent_f = ea.population().f;
  ea.Step(problem, rng);
  Eigen::MatrixXd child_f;
  EvaluateBatch(sphere, problem.batches().back(), child_f);
  std::vector<double> children(child_f.data(), child_f.data() + child_f.size());
  std::vector<double> parents(parent_f.data(), parent_f.data() + parent_f.size());
  std::sort(children.begin(), children.end());
  std::sort(parents.begin(), parents.end());
  std::vector<double> expected(children.begin(), children.begin() + 8);
  expected.insert(expected.end(), parents.begin(), parents.begin() + 2);
  std::sort(expected.begin(), expected.end());
  const Eigen::MatrixXd& f = ea.population().f;
  std::vector<double> survivors(f.data(), f.data() + f.size());
  std::sort(survivors.begin(), survivors.end());
  EXPECT_EQ(survivors, expected);
}

TEST(MuPlusLambdaTest, VarianceStopReportsConverged) {
  const auto problem = testing::ShiftedSphere(2);
  MuPlusLambdaParams params = Generic();
  params.variance_threshold = 1e-12;
  MuPlusLambdaEa ea(params);
  Rng rng(13);
  ea.Initialize(problem, rng);
  EXPECT_FALSE(ea.Converged());
  StopCriteria criteria;
  criteria.max_generations = 3000;
  StopTracker tracker(criteria);
  tracker.Update(ea, 0.0);
  EXPECT_EQ(Advance(problem, ea, tracker, rng), StopReason::kConverged);
  EXPECT_LT(ea.generation(), 3000u);
  const Eigen::ArrayXd f = ea.population().f.row(0).transpose().array();
  EXPECT_LT((f - f.mean()).square().mean(), 1e-12);

  // One step earlier the variance was still above the threshold.
  MuPlusLambdaEa again(params);
  RunGenerations(problem, again, ea.generation() - 1, 13);
  EXPECT_FALSE(again.Converged());
}

TEST(MuPlusLambdaTest, VarianceStopNeedsEveryObjective) {
  // f1 is constant, f2 is not: the population has not converged.
  const class : public Problem {
   public:
    const Eigen::VectorXd& lower() const override { return lo_; }
    const Eigen::VectorXd& upper() const override { return hi_; }
    std::size_t objectives() const override { return 2; }
    void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& c, std::span<double> f) const override {
      for (Eigen::Index i = 0; i < c.cols(); ++i) {
        f[2 * static_cast<std::size_t>(i)] = 1.0;
        f[2 * static_cast<std::size_t>(i) + 1] = c(0, i);
      }
    }

   private:
    Eigen::VectorXd lo_ = Eigen::VectorXd::Zero(2);
    Eigen::VectorXd hi_ = Eigen::VectorXd::Ones(2);
  } problem;
  MuPlusLambdaParams params = Generic();
  params.variance_threshold = 1e-3;
  MuPlusLambdaEa ea(params);
  Rng rng(14);
  ea.Initialize(problem, rng);
  EXPECT_FALSE(ea.Converged());
}

// A 20-dimensional sphere centred far from where random draws land, that knows a good start.
class SphereWithStart : public FunctionProblem {
 public:
  SphereWithStart()
      : FunctionProblem(Eigen::VectorXd::Constant(20, -10.0), Eigen::VectorXd::Constant(20, 10.0),
                        [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                          return (x.array() - 9.0).square().sum();
                        }) {}
  std::vector<Eigen::VectorXd> starts() const override {
    return {Eigen::VectorXd::Constant(20, 8.9), Eigen::VectorXd::Constant(20, -3.0)};
  }
};

TEST(MuPlusLambdaTest, FirstPopulationHoldsTheProblemsStartsAndTheSearchGoesOnFromThem) {
  const SphereWithStart problem;
  const FunctionProblem plain(
      problem.lower(), problem.upper(),
      [](const Eigen::Ref<const Eigen::VectorXd>& x) { return (x.array() - 9.0).square().sum(); });
  MuPlusLambdaEa started(Generic()), fresh(Generic());
  Rng rng(3), rng_fresh(3);
  started.Initialize(problem, rng);
  fresh.Initialize(plain, rng_fresh);
  EXPECT_TRUE(started.population().x.col(0).isApproxToConstant(8.9));
  EXPECT_TRUE(started.population().x.col(1).isApproxToConstant(-3.0));
  const double start_fitness = 20 * 0.1 * 0.1;
  EXPECT_NEAR(started.population().f.minCoeff(), start_fitness, 1e-12);
  EXPECT_GT(fresh.population().f.minCoeff(), 100 * start_fitness);
  // The rest of the first population is drawn as without starts.
  EXPECT_EQ(started.population().x.rightCols(8), fresh.population().x.rightCols(8));
  for (int g = 0; g < 30; ++g) {
    started.Step(problem, rng);
    fresh.Step(plain, rng_fresh);
  }
  EXPECT_LE(started.champion_f()(0), start_fitness + 1e-12);
  EXPECT_LT(started.population().f.minCoeff(), fresh.population().f.minCoeff());
}

TEST(MuPlusLambdaTest, OddLambdaMakesExactlyLambdaChildren) {
  MuPlusLambdaParams params = Generic();
  params.lambda = 9;
  MuPlusLambdaEa ea(params);
  const OptimResult r = RunFor(testing::ShiftedSphere(2), ea, 5, 15);
  EXPECT_EQ(r.evaluations, 10u + 9u * 5u);
}

TEST(MuPlusLambdaTest, ResultIndependentOfThreadCount) {
  const auto problem = Rosenbrock2();
  ExpectSameBitsWithOneAndTwoThreads([&] {
    MuPlusLambdaEa ea(Generic());
    return RunFor(problem, ea, 20, 16);
  });
  // 70 children of 100 genes: enough work for ZDT's evaluation to use both threads.
  ExpectSamePopulationWithOneAndTwoThreads(
      ZdtProblem(1, 100), [] { return std::make_unique<MuPlusLambdaEa>(Generic()); }, 10, 17);
}

TEST(MuPlusLambdaTest, ResumedRunMatchesUninterrupted) {
  MuPlusLambdaParams params;
  params.generation_limit = 20;  // the resumed half crosses the switch to group crossover
  ExpectResumeMatchesUninterrupted(
      ZdtProblem(2, 12), [&] { return std::make_unique<MuPlusLambdaEa>(params); }, 7, 20, 18);
  ExpectResumeMatchesUninterrupted(
      Rosenbrock2(), [] { return std::make_unique<MuPlusLambdaEa>(Generic()); }, 5, 12, 19);
}

TEST(MuPlusLambdaTest, RejectsBadParameters) {
  const auto rejects = [](auto change, const std::string& words) {
    testing::ExpectRejected<MuPlusLambdaEa, MuPlusLambdaParams>(change, words);
  };
  rejects([](MuPlusLambdaParams& p) { p.mu = 1; }, "mu");
  rejects([](MuPlusLambdaParams& p) { p.lambda = 0; }, "lambda");
  rejects([](MuPlusLambdaParams& p) { p.lambda = 5; }, "lambda (5) is smaller than the 8");
  rejects([](MuPlusLambdaParams& p) { p.q = 0; }, "tournament size q");
  rejects([](MuPlusLambdaParams& p) { p.pc = 1.5; }, "pc");
  rejects([](MuPlusLambdaParams& p) { p.pm = -0.1; }, "pm");
  rejects([](MuPlusLambdaParams& p) { p.c = 0.0; }, "mutation step c");
  rejects([](MuPlusLambdaParams& p) { p.gene_group = 0; }, "gene_group");
  rejects([](MuPlusLambdaParams& p) { p.column = 5; }, "column (5) must be a positive multiple");
  rejects([](MuPlusLambdaParams& p) { p.generation_limit = 0; }, "generation_limit");
  rejects([](MuPlusLambdaParams& p) { p.offspring_share = 1.2; }, "offspring_share");
  rejects([](MuPlusLambdaParams& p) { p.variance_threshold = -1.0; }, "variance_threshold");
}

TEST(MuPlusLambdaTest, DefaultsAreThoseOfPaper002) {
  const MuPlusLambdaParams params;
  EXPECT_EQ(params.mu, 10u);
  EXPECT_EQ(params.lambda, 70u);
  EXPECT_EQ(params.q, 5u);
  EXPECT_EQ(params.pc, 0.8);
  EXPECT_EQ(params.pm, 0.05);
  EXPECT_EQ(params.generation_limit, 100u);
  EXPECT_EQ(OffspringSurvivors(params), 8u);
  MuPlusLambdaEa ea(params);
  EXPECT_EQ(ea.name(), "mu+lambda");
  EXPECT_TRUE(ea.multi_objective());
}

}  // namespace
}  // namespace evoslam
