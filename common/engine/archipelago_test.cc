#include "common/engine/archipelago.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <vector>

#include "common/engine/engine_proto.h"
#include "common/optim/pareto.h"
#include "common/optim/test_problems.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

IslandModelParams DeIslands(std::size_t islands, Topology topology) {
  IslandModelParams p;
  p.islands = islands;
  p.algorithm.kind = AlgorithmKind::kDe;
  p.algorithm.de.strategy = DeStrategy::kRand1Bin;
  p.algorithm.de.population = 20;
  p.algorithm.de.f = 0.5;
  p.algorithm.de.cr = 0.2;
  p.migration.interval = 10;
  p.migration.migrants = 2;
  p.migration.topology = topology;
  return p;
}

StopCriteria Budget(std::size_t evaluations) {
  StopCriteria s;
  s.max_evaluations = evaluations;
  return s;
}

class TopologyTest : public ::testing::TestWithParam<Topology> {};

TEST_P(TopologyTest, SameBitsWithOneOrTwoThreads) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  const auto run = [&](std::size_t threads) {
    IslandModelParams p = DeIslands(4, GetParam());
    p.threads = threads;
    omp_set_num_threads(static_cast<int>(threads));
    Archipelago a(p, Budget(20000), 42);
    a.Run(problem);
    return a.Merged();
  };
  const int saved = omp_get_max_threads();
  const Population one = run(1);
  const Population two = run(2);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.x, two.x);
  EXPECT_EQ(one.f, two.f);
}

INSTANTIATE_TEST_SUITE_P(All, TopologyTest,
                         ::testing::Values(Topology::kRing, Topology::kBidirectionalRing,
                                           Topology::kFullyConnected, Topology::kStar,
                                           Topology::kRandom));

TEST(ArchipelagoTest, ResumesFromASerialisedCheckpointBitForBit) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 8);
  IslandModelParams p = DeIslands(3, Topology::kRandom);
  p.algorithm.kind = AlgorithmKind::kPso;
  p.algorithm.pso.particles = 15;
  Archipelago straight(p, Budget(15000), 7);
  straight.Run(problem);

  Archipelago first(p, Budget(15000), 7);
  first.Start(problem);
  for (int e = 0; e < 6; ++e) ASSERT_FALSE(first.RunEpoch(problem));
  std::string bytes;
  ASSERT_TRUE(ToProto(first.Checkpoint()).SerializeToString(&bytes));
  proto::ArchipelagoCheckpoint parsed;
  ASSERT_TRUE(parsed.ParseFromString(bytes));
  Archipelago resumed = Archipelago::FromCheckpoint(FromProto(parsed));
  resumed.Run(problem);

  EXPECT_EQ(resumed.epoch(), straight.epoch());
  EXPECT_EQ(resumed.evaluations(), straight.evaluations());
  EXPECT_EQ(resumed.Merged().x, straight.Merged().x);
  EXPECT_EQ(resumed.Best().best_fitness, straight.Best().best_fitness);
}

TEST(ArchipelagoTest, SharesTheEvaluationBudget) {
  const TestFunctionProblem problem(TestFunction::kSphere, 5);
  Archipelago a(DeIslands(4, Topology::kRing), Budget(4000), 1);
  EXPECT_EQ(a.Run(problem), StopReason::kEvaluations);
  // Each island stops at the first generation that reaches its quarter.
  EXPECT_GE(a.evaluations(), 4000u);
  EXPECT_LT(a.evaluations(), 4000u + 4 * 20);
}

TEST(ArchipelagoTest, MigrationHelpsOnRastrigin) {
  // The same budget spent by isolated islands (migrants never arrive) and by a ring that
  // exchanges its best: over several seeds the connected ring ends lower.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 20);
  double isolated = 0.0, connected = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    IslandModelParams p = DeIslands(4, Topology::kRing);
    p.algorithm.de.population = 12;
    p.algorithm.de.cr = 0.9;
    p.algorithm.de.f = 0.5;
    Archipelago with(p, Budget(30000), seed);
    with.Run(problem);
    connected += with.Best().best_fitness;
    p.migration.interval = 100000;  // no epoch ever ends before the budget does
    Archipelago without(p, Budget(30000), seed);
    without.Run(problem);
    isolated += without.Best().best_fitness;
  }
  EXPECT_LT(connected, 0.8 * isolated);
}

TEST(ArchipelagoTest, StopsAtTargetAndOnStagnation) {
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  StopCriteria target = Budget(1000000);
  target.target = 1e-6;
  Archipelago a(DeIslands(2, Topology::kRing), target, 3);
  EXPECT_EQ(a.Run(problem), StopReason::kTarget);
  EXPECT_LE(a.Best().best_fitness, 1e-6);
  EXPECT_LT(a.evaluations(), 100000u);

  // A flat function never improves after the first population.
  const FunctionProblem flat(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2),
                             [](const Eigen::Ref<const Eigen::VectorXd>&) { return 1.0; });
  StopCriteria stagnation;
  stagnation.stagnation_generations = 30;
  Archipelago b(DeIslands(2, Topology::kRing), stagnation, 3);
  EXPECT_EQ(b.Run(flat), StopReason::kStagnation);
  EXPECT_EQ(b.epoch(), 3u);
}

TEST(ArchipelagoTest, AsynchronousModeFinishesAndFindsTheOptimum) {
  const TestFunctionProblem problem(TestFunction::kSphere, 5);
  IslandModelParams p = DeIslands(3, Topology::kFullyConnected);
  p.asynchronous = true;
  Archipelago a(p, Budget(30000), 9);
  std::size_t reports = 0;
  EXPECT_EQ(a.Run(problem, [&](const EpochReport&) { ++reports; }), StopReason::kEvaluations);
  EXPECT_GE(a.evaluations(), 30000u);
  EXPECT_LT(a.Best().best_fitness, 1e-8);
  EXPECT_GE(reports, 3u);
}

TEST(ArchipelagoTest, ProgressReportsEveryEpoch) {
  const TestFunctionProblem problem(TestFunction::kSphere, 4);
  Archipelago a(DeIslands(2, Topology::kRing), Budget(2 * 20 * 51), 2);
  std::vector<EpochReport> reports;
  a.Run(problem, [&](const EpochReport& r) { reports.push_back(r); });
  ASSERT_EQ(reports.size(), 5u);
  for (std::size_t k = 1; k < reports.size(); ++k) {
    EXPECT_EQ(reports[k].epoch, k + 1);
    EXPECT_GT(reports[k].evaluations, reports[k - 1].evaluations);
    EXPECT_LE(reports[k].best, reports[k - 1].best);  // migration keeps every island's best
  }
}

TEST(ArchipelagoTest, ImmuneIslandsShareAParetoFront) {
  // Multi-objective islands migrate their best by Pareto rank; the merged first front of four
  // immune MOEA islands on ZDT1 lies close to the true front, identically with 1 and 2 threads.
  const ZdtProblem problem(1, 10);
  IslandModelParams p;
  p.islands = 4;
  p.algorithm.kind = AlgorithmKind::kImmune;
  p.algorithm.immune.population = 30;
  p.algorithm.immune.recombinations = 24;
  p.algorithm.immune.mutations = 6;
  p.migration.interval = 10;
  p.migration.migrants = 3;
  const auto run = [&](std::size_t threads) {
    p.threads = threads;
    Archipelago a(p, Budget(24000), 5);
    a.Run(problem);
    return a.Merged();
  };
  const Population one = run(1);
  const Population two = run(2);
  EXPECT_EQ(one.f, two.f);
  const std::vector<std::size_t> front = FirstFront(one.f);
  Eigen::MatrixXd f(2, static_cast<Eigen::Index>(front.size()));
  for (std::size_t k = 0; k < front.size(); ++k)
    f.col(static_cast<Eigen::Index>(k)) = one.f.col(static_cast<Eigen::Index>(front[k]));
  EXPECT_LT(InvertedGenerationalDistance(problem, f), 0.02);
}

TEST(ArchipelagoTest, RefusesBadSettings) {
  IslandModelParams none = DeIslands(0, Topology::kRing);
  EXPECT_THROW(Archipelago(none, Budget(10), 1), Error);
  IslandModelParams crowd = DeIslands(2, Topology::kRing);
  crowd.migration.migrants = 20;
  EXPECT_THROW(Archipelago(crowd, Budget(10), 1), Error);
  EXPECT_THROW(Archipelago(DeIslands(2, Topology::kRing), StopCriteria{}, 1), Error);
}

}  // namespace
}  // namespace evoslam
