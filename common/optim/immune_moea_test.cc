#include "common/optim/immune_moea.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "common/optim/immunity.h"
#include "common/optim/optim_testing.h"
#include "common/optim/pareto.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::ExpectResumeMatchesUninterrupted;
using testing::ExpectSamePopulationWithOneAndTwoThreads;
using testing::RecordingProblem;
using testing::RunGenerations;

// ZDT knowledge: the front lies where the tail x_2..x_n is 0. The vaccine pulls five random tail
// genes towards 0 (each times a uniform factor in [0, 1.5), so it may also push them away), and
// immune selection keeps the vaccinated child only when its tail sum went down.
class TailImmunity : public Immunity {
 public:
  bool Vaccinate(Eigen::Ref<Eigen::VectorXd> x, Rng& rng) const override {
    const auto tail = static_cast<std::size_t>(x.size() - 1);
    for (int k = 0; k < 5; ++k) {
      const auto j = 1 + static_cast<Eigen::Index>(rng.UniformIndex(tail));
      x(j) = std::min(1.0, x(j) * rng.Uniform(0.0, 1.5));
    }
    return true;
  }
  bool Accept(const Eigen::Ref<const Eigen::VectorXd>& original,
              const Eigen::Ref<const Eigen::VectorXd>& vaccinated, Rng& /*rng*/) const override {
    return vaccinated.tail(vaccinated.size() - 1).sum() < original.tail(original.size() - 1).sum();
  }
};

class ImmuneZdt : public ZdtProblem {
 public:
  using ZdtProblem::ZdtProblem;
  const Immunity* immunity() const override { return &immunity_; }

 private:
  TailImmunity immunity_;
};

// Two objectives, the squared distances to (0.3, 0.3, 0.3) and (0.32, 0.32, 0.32): the Pareto
// set is the short segment between them, where a population soon converges.
class TwoPoints : public Problem {
 public:
  const Eigen::VectorXd& lower() const override { return lo_; }
  const Eigen::VectorXd& upper() const override { return hi_; }
  std::size_t objectives() const override { return 2; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& c, std::span<double> f) const override {
    for (Eigen::Index i = 0; i < c.cols(); ++i) {
      f[2 * static_cast<std::size_t>(i)] = (c.col(i).array() - 0.3).square().sum();
      f[2 * static_cast<std::size_t>(i) + 1] = (c.col(i).array() - 0.32).square().sum();
    }
  }
  // Distance from x to the Pareto set.
  static double Distance(const Eigen::Ref<const Eigen::VectorXd>& x) {
    const double t = std::clamp((x.array() - 0.3).mean() / 0.02, 0.0, 1.0);
    return (x.array() - (0.3 + 0.02 * t)).matrix().norm();
  }

 private:
  Eigen::VectorXd lo_ = Eigen::VectorXd::Zero(3);
  Eigen::VectorXd hi_ = Eigen::VectorXd::Ones(3);
};

ImmuneMoeaParams Restarting() {
  ImmuneMoeaParams params;
  params.restart_spread = 0.05;  // the Pareto set spans 0.02 of the box along each coordinate
  return params;
}

double FrontIgd(const ZdtProblem& problem, const ImmuneMoea& moea) {
  return InvertedGenerationalDistance(problem, moea.Front().f);
}

void RunEvaluations(const Problem& problem, ImmuneMoea& moea, std::size_t budget,
                    std::uint64_t seed) {
  Rng rng(seed);
  moea.Initialize(problem, rng);
  while (moea.evaluations() < budget) moea.Step(problem, rng);
}

// Starts `moea` on `problem` from the population x (no archive).
void StartFrom(ImmuneMoea& moea, const Problem& problem, const Eigen::MatrixXd& x) {
  Rng rng(0);
  moea.Initialize(problem, rng);
  AlgorithmState state = moea.Save();
  state.population.x = x;
  EvaluateBatch(problem, x, state.population.f);
  moea.Restore(state);
}

class ImmuneZdtTest : public ::testing::TestWithParam<int> {};

TEST_P(ImmuneZdtTest, ApproachesTheWholeFront) {
  // About 0.0075 is the best 50 points spread along the front can do.
  const ZdtProblem problem(GetParam(), 10);
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    ImmuneMoea moea(ImmuneMoeaParams{});
    RunEvaluations(problem, moea, 20000, seed);
    const double igd = FrontIgd(problem, moea);
    RecordProperty("igd_seed_" + std::to_string(seed), std::to_string(igd));
    EXPECT_LT(igd, 0.012) << "seed " << seed;
    EXPECT_LT(moea.Front().f.row(0).minCoeff(), 0.01) << "seed " << seed;
    EXPECT_GT(moea.Front().f.row(0).maxCoeff(), 0.99) << "seed " << seed;
  }
}

TEST_P(ImmuneZdtTest, UniformRecombinationAlsoApproachesTheFront) {
  const ZdtProblem problem(GetParam(), 10);
  ImmuneMoeaParams params;
  params.recombination = ImmuneRecombination::kUniform;
  ImmuneMoea moea(params);
  RunEvaluations(problem, moea, 20000, 1);
  const double igd = FrontIgd(problem, moea);
  RecordProperty("igd", std::to_string(igd));
  EXPECT_LT(igd, 0.05);
}

TEST_P(ImmuneZdtTest, ImmunityGivesABetterFrontForTheSameBudget) {
  // 30 genes and 3000 evaluations: far from converged, where problem knowledge pays most.
  const ImmuneZdt immune(GetParam(), 30);
  const ZdtProblem plain(GetParam(), 30);
  double with = 0.0;
  double without = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    ImmuneMoea a(ImmuneMoeaParams{});
    RunEvaluations(immune, a, 3000, seed);
    with += FrontIgd(plain, a) / 5;
    ImmuneMoea b(ImmuneMoeaParams{});
    RunEvaluations(plain, b, 3000, seed);
    without += FrontIgd(plain, b) / 5;
  }
  RecordProperty("igd_with_immunity", std::to_string(with));
  RecordProperty("igd_without_immunity", std::to_string(without));
  EXPECT_LT(with, 0.6 * without);
}

INSTANTIATE_TEST_SUITE_P(Zdt1And2, ImmuneZdtTest, ::testing::Values(1, 2));

// Marks every vaccinated candidate by setting x(0) to a value no operator makes; Accept answers
// as told, after checking it sees the original and the vaccinated candidate.
class MarkingImmunity : public Immunity {
 public:
  static constexpr double kMark = 0.123456789;
  explicit MarkingImmunity(bool accept) : accept_(accept) {}
  bool Vaccinate(Eigen::Ref<Eigen::VectorXd> x, Rng& /*rng*/) const override {
    x(0) = kMark;
    return true;
  }
  bool Accept(const Eigen::Ref<const Eigen::VectorXd>& original,
              const Eigen::Ref<const Eigen::VectorXd>& vaccinated, Rng& /*rng*/) const override {
    EXPECT_NE(original(0), kMark);
    EXPECT_EQ(vaccinated(0), kMark);
    EXPECT_EQ(original.tail(original.size() - 1), vaccinated.tail(vaccinated.size() - 1));
    return accept_;
  }

 private:
  bool accept_;
};

class MarkedZdt : public ZdtProblem {
 public:
  explicit MarkedZdt(bool accept) : ZdtProblem(1, 5), immunity_(accept) {}
  const Immunity* immunity() const override { return &immunity_; }

 private:
  MarkingImmunity immunity_;
};

// With one objective the Pareto order is a plain sort by fitness, and the immune MOEA is a
// single-objective optimiser like the others.
TEST(ImmuneMoeaTest, SolvesSingleObjectiveSphereRosenbrockAndRastrigin) {
  double sphere = 0.0, rosenbrock = 0.0, rastrigin = 0.0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    ImmuneMoea a(ImmuneMoeaParams{}), b(ImmuneMoeaParams{}), c(ImmuneMoeaParams{});
    sphere = std::max(
        sphere,
        testing::RunFor(TestFunctionProblem(TestFunction::kSphere, 10), a, 400, seed).best_fitness);
    rosenbrock = std::max(
        rosenbrock, testing::RunFor(TestFunctionProblem(TestFunction::kRosenbrock, 2), b, 400, seed)
                        .best_fitness);
    rastrigin += testing::RunFor(TestFunctionProblem(TestFunction::kRastrigin, 10), c, 400, seed)
                     .best_fitness;
  }
  // Measured: worst sphere 3e-4, worst Rosenbrock 3e-6, mean Rastrigin 2.4; random sampling of
  // the same 20 000 points ends near 10, 0.04 and 60.
  EXPECT_LT(sphere, 2e-3);
  EXPECT_LT(rosenbrock, 1e-4);
  EXPECT_LT(rastrigin / 3, 5.0);
}

TEST(ImmuneMoeaTest, ImmuneSelectionDecidesWhetherTheVaccinatedChildIsKept) {
  ImmuneMoeaParams params;
  params.recombinations = 1500;
  params.mutations = 1500;
  for (const bool accept : {true, false}) {
    const MarkedZdt marked(accept);
    const RecordingProblem problem(marked);
    ImmuneMoea moea(params);
    RunGenerations(problem, moea, 1, 20);
    const Eigen::MatrixXd& children = problem.batches().back();
    const double share =
        static_cast<double>((children.row(0).array() == MarkingImmunity::kMark).count()) /
        static_cast<double>(children.cols());
    // Vaccinated children differ from their source, so they are all evaluated; the others only
    // when recombination or mutation changed them, about 0.9 * 1500 + 0.34 * 1500 of 3000.
    if (accept) {
      EXPECT_NEAR(share, 0.3 / (0.3 + 0.7 * (0.9 + 0.34) / 2), 0.04);
    } else {
      EXPECT_EQ(share, 0.0);
    }
  }
}

TEST(ImmuneMoeaTest, BlendChildrenFillTheParentsIntervalWidenedByAlpha) {
  // Two parents 0.4 and 0.6 in every gene: BLX-0.5 children are uniform in [0.3, 0.7].
  const ZdtProblem zdt(1, 4);
  const RecordingProblem problem(zdt);
  ImmuneMoeaParams params;
  params.population = 2;
  params.recombinations = 2000;
  params.mutations = 0;
  params.p_recombination = 1.0;
  ImmuneMoea moea(params);
  Eigen::MatrixXd parents(4, 2);
  parents.col(0).setConstant(0.4);
  parents.col(1).setConstant(0.6);
  StartFrom(moea, problem, parents);
  Rng rng(21);
  moea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  // Parent 0.4 dominates 0.6 on ZDT1, so a binary tournament returns it unless both draws are
  // 0.6: the parents differ in 2 * 3/4 * 1/4 of the pairs; the others make copies, not evaluated.
  EXPECT_NEAR(static_cast<double>(children.cols()), 2000.0 * 0.375, 65.0);
  EXPECT_GE(children.minCoeff(), 0.3);
  EXPECT_LE(children.maxCoeff(), 0.7);
  EXPECT_LT(children.minCoeff(), 0.302);
  EXPECT_GT(children.maxCoeff(), 0.698);
  EXPECT_NEAR(children.mean(), 0.5, 0.005);
}

TEST(ImmuneMoeaTest, UniformChildrenTakeEachGeneFromAParent) {
  const ZdtProblem zdt(1, 6);
  const RecordingProblem problem(zdt);
  ImmuneMoeaParams params;
  params.population = 2;
  params.recombinations = 400;
  params.mutations = 0;
  params.p_recombination = 1.0;
  params.recombination = ImmuneRecombination::kUniform;
  ImmuneMoea moea(params);
  Eigen::MatrixXd parents(6, 2);
  parents.col(0).setConstant(0.4);
  parents.col(1).setConstant(0.6);
  StartFrom(moea, problem, parents);
  Rng rng(22);
  moea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  EXPECT_EQ(((children.array() == 0.4) || (children.array() == 0.6)).count(), children.size());
  EXPECT_NEAR((children.array() == 0.4).count(), children.size() / 2, children.size() / 10);
}

TEST(ImmuneMoeaTest, MutationResetsEachGeneWithProbabilityPM) {
  const ZdtProblem zdt(1, 10);
  const RecordingProblem problem(zdt);
  ImmuneMoeaParams params;
  params.population = 5;
  params.recombinations = 0;
  params.mutations = 1000;
  params.restart_spread = 0.0;  // the population of copies has converged; no restart wanted
  ImmuneMoea moea(params);
  StartFrom(moea, problem, Eigen::MatrixXd::Constant(10, 5, 0.5));
  Rng rng(23);
  moea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  // Children with no gene reset are copies and are not evaluated: 1 - 0.92^10 of them are.
  EXPECT_NEAR(static_cast<double>(children.cols()), 1000.0 * (1 - std::pow(0.92, 10)), 50.0);
  const Eigen::ArrayXXd reset = children.array();
  const auto changed = (reset != 0.5).count();
  EXPECT_NEAR(static_cast<double>(changed), 800.0, 85.0);  // 1000 * 10 * 0.08, 3 sigma
  const double mean = ((reset != 0.5).select(reset, 0.0)).sum() / static_cast<double>(changed);
  EXPECT_NEAR(mean, 0.5, 0.035);
  EXPECT_LT(children.minCoeff(), 0.01);
  EXPECT_GT(children.maxCoeff(), 0.99);
}

TEST(ImmuneMoeaTest, AGenerationWithoutChangesCostsNothing) {
  ImmuneMoeaParams params;
  params.p_recombination = 0.0;
  params.p_mutation = 0.0;
  ImmuneMoea moea(params);
  const ZdtProblem problem(1, 5);
  RunGenerations(problem, moea, 3, 24);
  EXPECT_EQ(moea.evaluations(), 50u);
  EXPECT_EQ(moea.generation(), 3u);
}

TEST(ImmuneMoeaTest, RestartsOnConvergenceAndTheArchiveKeepsTheFront) {
  const TwoPoints problem;
  ImmuneMoea moea(Restarting());
  Rng rng(25);
  moea.Initialize(problem, rng);
  Population converged;
  for (int g = 0; g < 60 && moea.restarts() == 0; ++g) {
    converged = moea.population();
    const bool should_restart = moea.PopulationConverged(problem);
    const std::size_t evaluations = moea.evaluations();
    moea.Step(problem, rng);
    ASSERT_EQ(moea.restarts(), should_restart ? 1u : 0u);
    if (should_restart) {
      EXPECT_EQ(moea.evaluations(), evaluations + 50);
    }
  }
  ASSERT_EQ(moea.restarts(), 1u);

  // The archive is the first front of the converged population, each member once.
  const std::vector<std::size_t> front = FirstFront(converged.f);
  const Population& archive = moea.archive();
  EXPECT_EQ(static_cast<std::size_t>(archive.x.cols()), std::min<std::size_t>(50, front.size()));
  for (Eigen::Index a = 0; a < archive.x.cols(); ++a) {
    const bool found = std::any_of(front.begin(), front.end(), [&](std::size_t i) {
      return converged.x.col(static_cast<Eigen::Index>(i)) == archive.x.col(a);
    });
    EXPECT_TRUE(found) << "archive member " << a << " is not on the converged front";
  }
  // The new population is random again: spread over most of the box.
  EXPECT_FALSE(moea.PopulationConverged(problem));
  const Eigen::VectorXd spread =
      moea.population().x.rowwise().maxCoeff() - moea.population().x.rowwise().minCoeff();
  EXPECT_GT(spread.minCoeff(), 0.8);

  // Later results never lose ground: each point of the converged front is matched or dominated.
  for (int g = 0; g < 15; ++g) moea.Step(problem, rng);
  const Population result = moea.Front();
  for (const std::size_t i : front) {
    const auto point = converged.f.col(static_cast<Eigen::Index>(i));
    bool covered = false;
    for (Eigen::Index r = 0; r < result.f.cols(); ++r)
      covered = covered || result.f.col(r) == point || Dominates(result.f.col(r), point);
    EXPECT_TRUE(covered) << "converged front point " << i << " was lost";
  }
}

TEST(ImmuneMoeaTest, TheArchiveTakesPartInParentSelection) {
  // Right after a restart P is random; children close to the Pareto set can only come from
  // archive parents, and binary tournaments prefer those.
  const TwoPoints two_points;
  const RecordingProblem problem(two_points);
  ImmuneMoeaParams params = Restarting();
  params.recombinations = 1000;
  ImmuneMoea moea(params);
  Rng rng(26);
  moea.Initialize(problem, rng);
  while (moea.restarts() == 0 && moea.generation() < 60) moea.Step(problem, rng);
  ASSERT_EQ(moea.restarts(), 1u);
  moea.Step(problem, rng);
  const Eigen::MatrixXd& children = problem.batches().back();
  int near = 0;
  for (Eigen::Index k = 0; k < children.cols(); ++k)
    near += TwoPoints::Distance(children.col(k)) < 0.02 ? 1 : 0;
  // Both parents come from the archive in about (1 - (50 / (50 + archive size))^2)^2 of the
  // recombinations, over 10 % here; two random parents almost never land that close.
  EXPECT_GT(near, children.cols() / 20);
}

TEST(ImmuneMoeaTest, ResultIndependentOfThreadCount) {
  // Batches of about 50 candidates of 100 genes: enough for ZDT's evaluation to use both threads.
  ExpectSamePopulationWithOneAndTwoThreads(
      ImmuneZdt(1, 100), [] { return std::make_unique<ImmuneMoea>(ImmuneMoeaParams{}); }, 10, 27);
}

TEST(ImmuneMoeaTest, ResumedRunMatchesUninterruptedAcrossRestarts) {
  // The first restart comes within about a dozen generations, so the checkpoint holds an archive.
  ExpectResumeMatchesUninterrupted(
      TwoPoints(), [] { return std::make_unique<ImmuneMoea>(Restarting()); }, 20, 40, 28,
      [](const ImmuneMoea& after, const ImmuneMoea& straight) {
        EXPECT_GT(straight.restarts(), 1u);
        EXPECT_EQ(after.restarts(), straight.restarts());
        EXPECT_EQ(after.archive().x, straight.archive().x);
        EXPECT_EQ(after.archive().f, straight.archive().f);
      });
  ExpectResumeMatchesUninterrupted(
      ImmuneZdt(2, 8), [] { return std::make_unique<ImmuneMoea>(ImmuneMoeaParams{}); }, 6, 15, 29);
}

TEST(ImmuneMoeaTest, RestoreRefusesAMissingOrMisshapenArchive) {
  ImmuneMoea moea(Restarting());
  Rng rng(30);
  moea.Initialize(TwoPoints(), rng);
  const AlgorithmState good = moea.Save();
  AlgorithmState missing = good;
  missing.memory.erase("archive_x");
  EXPECT_THROW(ImmuneMoea(Restarting()).Restore(missing), Error);
  AlgorithmState misshapen = good;
  misshapen.memory["archive_x"] = Eigen::MatrixXd::Zero(3, 2);  // fitness has 0 columns
  EXPECT_THROW(ImmuneMoea(Restarting()).Restore(misshapen), Error);
  AlgorithmState no_count = good;
  no_count.memory.erase("restarts");
  EXPECT_THROW(ImmuneMoea(Restarting()).Restore(no_count), Error);
}

TEST(ImmuneMoeaTest, RejectsBadParameters) {
  const auto rejects = [](auto change, const std::string& words) {
    testing::ExpectRejected<ImmuneMoea, ImmuneMoeaParams>(change, words);
  };
  rejects([](ImmuneMoeaParams& p) { p.population = 1; }, "population");
  rejects(
      [](ImmuneMoeaParams& p) {
        p.recombinations = 0;
        p.mutations = 0;
      },
      "no candidate is ever made");
  rejects([](ImmuneMoeaParams& p) { p.p_recombination = 1.1; }, "p_recombination");
  rejects([](ImmuneMoeaParams& p) { p.p_immunity = -0.1; }, "p_immunity");
  rejects([](ImmuneMoeaParams& p) { p.p_mutation = 2.0; }, "p_mutation");
  rejects([](ImmuneMoeaParams& p) { p.blend_alpha = -0.5; }, "blend_alpha");
  rejects([](ImmuneMoeaParams& p) { p.restart_spread = 1.5; }, "restart_spread");
  rejects([](ImmuneMoeaParams& p) { p.archive_size = 0; }, "archive_size");
}

TEST(ImmuneMoeaTest, DefaultsAreThoseOfPaper004) {
  const ImmuneMoeaParams params;
  EXPECT_EQ(params.population, 50u);
  EXPECT_EQ(params.p_recombination, 0.9);
  EXPECT_EQ(params.p_immunity, 0.3);
  EXPECT_EQ(params.p_mutation, 0.08);
  ImmuneMoea moea(params);
  EXPECT_EQ(moea.name(), "immune");
  EXPECT_TRUE(moea.multi_objective());
  EXPECT_FALSE(moea.Converged());
}

}  // namespace
}  // namespace evoslam
