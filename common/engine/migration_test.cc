#include "common/engine/migration.h"

#include <gtest/gtest.h>

#include <set>

#include "common/optim/differential_evolution.h"
#include "common/optim/test_problems.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(MigrationSourcesTest, RingFullyConnectedAndStar) {
  Rng rng(1);
  const auto ring = MigrationSources(Topology::kRing, 4, rng);
  EXPECT_EQ(ring[0], std::vector<std::size_t>{3});
  EXPECT_EQ(ring[2], std::vector<std::size_t>{1});
  const auto both = MigrationSources(Topology::kBidirectionalRing, 4, rng);
  EXPECT_EQ(both[0], (std::vector<std::size_t>{3, 1}));
  EXPECT_EQ(both[2], (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(MigrationSources(Topology::kBidirectionalRing, 2, rng)[1], std::vector<std::size_t>{0});
  const auto full = MigrationSources(Topology::kFullyConnected, 3, rng);
  EXPECT_EQ(full[1], (std::vector<std::size_t>{0, 2}));
  const auto star = MigrationSources(Topology::kStar, 4, rng);
  EXPECT_EQ(star[0], (std::vector<std::size_t>{1, 2, 3}));
  EXPECT_EQ(star[3], std::vector<std::size_t>{0});
  EXPECT_TRUE(MigrationSources(Topology::kRing, 1, rng)[0].empty());
}

TEST(MigrationSourcesTest, RandomNeverSelfAndCoversOthers) {
  Rng rng(2);
  std::set<std::size_t> seen;
  for (int epoch = 0; epoch < 200; ++epoch) {
    const auto s = MigrationSources(Topology::kRandom, 5, rng);
    for (std::size_t i = 0; i < 5; ++i) {
      ASSERT_EQ(s[i].size(), 1u);
      EXPECT_NE(s[i][0], i);
    }
    seen.insert(s[2][0]);
  }
  EXPECT_EQ(seen, (std::set<std::size_t>{0, 1, 3, 4}));
}

TEST(MigrationTest, NamesRoundTripAndBadNamesAreRefused) {
  for (const Topology t : {Topology::kRing, Topology::kBidirectionalRing, Topology::kFullyConnected,
                           Topology::kStar, Topology::kRandom})
    EXPECT_EQ(ParseTopology(TopologyName(t)), t);
  EXPECT_THROW(ParseTopology("torus"), Error);
  EXPECT_THROW(ParseMigrationPolicy("worst"), Error);
  MigrationParams p;
  p.interval = 0;
  EXPECT_THROW(ValidateMigrationParams(p, 10), Error);
  p.interval = 5;
  p.migrants = 10;
  EXPECT_THROW(ValidateMigrationParams(p, 10), Error);
}

// A DE island on the sphere whose population we can inspect.
DifferentialEvolution StartedIsland(std::uint64_t seed) {
  DeParams params;
  params.population = 8;
  DifferentialEvolution de(params);
  Rng rng(seed);
  de.Initialize(TestFunctionProblem(TestFunction::kSphere, 3), rng);
  return de;
}

TEST(MigrationTest, BestEmigrantsAreTheBestInOrder) {
  const DifferentialEvolution island = StartedIsland(3);
  MigrationParams params;
  params.migrants = 3;
  Rng rng(1);
  const Migrants m = SelectEmigrants(island.population(), params, rng);
  ASSERT_EQ(m.size(), 3u);
  std::vector<double> f(island.population().f.data(),
                        island.population().f.data() + island.population().f.size());
  std::sort(f.begin(), f.end());
  for (Eigen::Index k = 0; k < 3; ++k) EXPECT_EQ(m.f(0, k), f[static_cast<std::size_t>(k)]);
}

TEST(MigrationTest, BestReplaceWorstOnlyReplacesWorseResidents) {
  DifferentialEvolution island = StartedIsland(4);
  const Population before = island.population();
  Migrants m;
  m.x = Eigen::MatrixXd::Zero(3, 2);
  m.f.resize(1, 2);
  m.f << -1.0, 1e9;  // one better than everyone, one worse than everyone
  Rng rng(1);
  Immigrate(island, m, MigrationPolicy::kBestReplaceWorst, rng);
  const Population& after = island.population();
  EXPECT_EQ(after.f.row(0).minCoeff(), -1.0);
  EXPECT_LT(after.f.row(0).maxCoeff(), 1e9);
  // Exactly one resident left, and it was the worst.
  int changed = 0;
  for (Eigen::Index i = 0; i < 8; ++i) {
    if (after.f(0, i) != before.f(0, i)) {
      ++changed;
      EXPECT_EQ(before.f(0, i), before.f.row(0).maxCoeff());
    }
  }
  EXPECT_EQ(changed, 1);
}

TEST(MigrationTest, RandomReplaceKeepsTheIslandsBest) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    DifferentialEvolution island = StartedIsland(seed);
    const double best = island.population().f.row(0).minCoeff();
    Migrants m;
    m.x = Eigen::MatrixXd::Zero(3, 7);
    m.f = Eigen::MatrixXd::Constant(1, 7, 1e9);
    Rng rng(seed);
    Immigrate(island, m, MigrationPolicy::kRandomReplace, rng);
    EXPECT_EQ(island.population().f.row(0).minCoeff(), best);
    EXPECT_EQ((island.population().f.array() == 1e9).count(), 7);
  }
}

TEST(MigrationTest, ImmigrantsOfAnotherProblemAreRefused) {
  DifferentialEvolution island = StartedIsland(5);
  Migrants m;
  m.x = Eigen::MatrixXd::Zero(4, 1);
  m.f = Eigen::MatrixXd::Zero(1, 1);
  Rng rng(1);
  EXPECT_THROW(Immigrate(island, m, MigrationPolicy::kBestReplaceWorst, rng), Error);
}

}  // namespace
}  // namespace evoslam
