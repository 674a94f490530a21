#include "common/optim/pareto.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "common/util/infinity.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

Eigen::MatrixXd Columns(std::initializer_list<std::initializer_list<double>> points) {
  const auto rows = static_cast<Eigen::Index>(points.begin()->size());
  Eigen::MatrixXd f(rows, static_cast<Eigen::Index>(points.size()));
  Eigen::Index i = 0;
  for (const auto& point : points) {
    Eigen::Index k = 0;
    for (const double v : point) f(k++, i) = v;
    ++i;
  }
  return f;
}

TEST(ParetoTest, DominanceNeedsOneStrictImprovement) {
  EXPECT_TRUE(Dominates(Eigen::Vector2d(1, 2), Eigen::Vector2d(1, 3)));
  EXPECT_FALSE(Dominates(Eigen::Vector2d(1, 3), Eigen::Vector2d(1, 2)));
  EXPECT_FALSE(Dominates(Eigen::Vector2d(1, 2), Eigen::Vector2d(1, 2)));
  EXPECT_FALSE(Dominates(Eigen::Vector2d(0, 3), Eigen::Vector2d(1, 2)));
}

TEST(ParetoTest, RanksThreeFrontsBuiltByConstruction) {
  // Front 0: (1,5) (2,3) (4,1); each point of front 1 is a front-0 point moved up or right, and
  // (6,6) lies behind all of front 1. The columns are shuffled so that index order does not help.
  const Eigen::MatrixXd f = Columns({{3, 4}, {6, 6}, {1, 5}, {5, 2}, {4, 1}, {2, 6}, {2, 3}});
  EXPECT_EQ(NonDominatedRanks(f), (std::vector<std::size_t>{1, 2, 0, 1, 0, 1, 0}));
  EXPECT_EQ(FirstFront(f), (std::vector<std::size_t>{2, 4, 6}));
}

TEST(ParetoTest, RanksThreeObjectives) {
  const Eigen::MatrixXd f = Columns({{1, 1, 2}, {0, 0, 1}, {1, 1, 1}, {0, 1, 0}, {1, 0, 0}});
  EXPECT_EQ(NonDominatedRanks(f), (std::vector<std::size_t>{2, 0, 1, 0, 0}));
}

TEST(ParetoTest, RanksMatchTheDefinitionOnRandomSets) {
  // Rank r means: dominated by some member of rank r - 1 and by no member of rank r or more.
  Rng rng(5);
  Eigen::MatrixXd f(3, 60);
  for (Eigen::Index i = 0; i < f.cols(); ++i) {
    for (Eigen::Index k = 0; k < 3; ++k) f(k, i) = std::round(rng.Uniform(0, 6));
  }
  const std::vector<std::size_t> rank = NonDominatedRanks(f);
  ASSERT_GT(*std::max_element(rank.begin(), rank.end()), 2u);
  for (Eigen::Index i = 0; i < f.cols(); ++i) {
    const std::size_t r = rank[static_cast<std::size_t>(i)];
    bool by_previous = false;
    for (Eigen::Index j = 0; j < f.cols(); ++j) {
      const std::size_t rj = rank[static_cast<std::size_t>(j)];
      if (!Dominates(f.col(j), f.col(i))) continue;
      EXPECT_LT(rj, r) << i << " is dominated by " << j << " of the same or a later front";
      by_previous = by_previous || rj + 1 == r;
    }
    EXPECT_EQ(by_previous, r > 0) << i;
  }
}

TEST(ParetoTest, CrowdingDistancesOfAHandBuiltFront) {
  // One front spanning 10 in both objectives: interior distances are the neighbour gaps / 10.
  const Eigen::MatrixXd f = Columns({{3, 2}, {0, 10}, {6, 1}, {10, 0}, {1, 6}, {12, 12}});
  const ParetoRanking ranking = RankPareto(f);
  EXPECT_EQ(ranking.rank, (std::vector<std::size_t>{0, 0, 0, 0, 0, 1}));
  EXPECT_NEAR(ranking.crowding[0], 0.5 + 0.5, 1e-12);  // (6-1)/10 + (6-1)/10
  EXPECT_EQ(ranking.crowding[1], kInfinity);
  EXPECT_NEAR(ranking.crowding[2], 0.7 + 0.2, 1e-12);  // (10-3)/10 + (2-0)/10
  EXPECT_EQ(ranking.crowding[3], kInfinity);
  EXPECT_NEAR(ranking.crowding[4], 0.3 + 0.8, 1e-12);  // (3-0)/10 + (10-2)/10
  EXPECT_EQ(ranking.crowding[5], 0.0);                 // alone in its front
  EXPECT_EQ(ranking.Order(), (std::vector<std::size_t>{1, 3, 4, 0, 2, 5}));
}

TEST(ParetoTest, DuplicatesShareARankAndFallBackToIndexOrder) {
  // Two copies of (1,1) neither dominate each other; (1,2) is dominated by both (equal in f1).
  const Eigen::MatrixXd f = Columns({{1, 2}, {1, 1}, {1, 1}});
  const ParetoRanking ranking = RankPareto(f);
  EXPECT_EQ(ranking.rank, (std::vector<std::size_t>{1, 0, 0}));
  EXPECT_EQ(ranking.crowding, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(ranking.Order(), (std::vector<std::size_t>{1, 2, 0}));
  EXPECT_TRUE(ranking.Before(1, 2));
  EXPECT_FALSE(ranking.Before(2, 1));
  EXPECT_FALSE(ranking.Before(1, 1));
}

TEST(ParetoTest, CopiesOfAnExtremeShareItsTwoEnds) {
  // Ties sort by index: the first copy of (0,4) ends f1's order, the second ends f2's.
  const Eigen::MatrixXd f = Columns({{0, 4}, {0, 4}, {2, 2}, {4, 0}});
  const std::vector<double> d = RankPareto(f).crowding;
  EXPECT_EQ(d[0], kInfinity);
  EXPECT_EQ(d[1], kInfinity);
  EXPECT_NEAR(d[2], 4.0 / 4.0 + 4.0 / 4.0, 1e-12);
  EXPECT_EQ(d[3], kInfinity);
}

TEST(ParetoTest, NanCountsAsWorst) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // (NaN, -100) would be non-dominated if only its NaN were worst; the whole column counts as
  // worst.
  const Eigen::MatrixXd f = Columns({{nan, -100}, {5, 5}, {1e300, 1e300}, {0, nan}});
  const ParetoRanking ranking = RankPareto(f);
  EXPECT_EQ(ranking.rank, (std::vector<std::size_t>{2, 0, 1, 2}));
  EXPECT_EQ(ranking.crowding, (std::vector<double>{0, 0, 0, 0}));
  EXPECT_EQ(ranking.Order(), (std::vector<std::size_t>{1, 2, 0, 3}));
  EXPECT_EQ(FirstFront(f), (std::vector<std::size_t>{1}));
}

TEST(ParetoTest, SingleObjectiveDegeneratesToSorting) {
  Rng rng(3);
  Eigen::MatrixXd f(1, 40);
  for (Eigen::Index i = 0; i < f.cols(); ++i) f(0, i) = std::round(rng.Uniform(0, 10));
  const ParetoRanking ranking = RankPareto(f);
  std::vector<std::size_t> sorted(40);
  std::iota(sorted.begin(), sorted.end(), std::size_t{0});
  std::stable_sort(sorted.begin(), sorted.end(),
                   [&](std::size_t a, std::size_t b) { return f(0, a) < f(0, b); });
  EXPECT_EQ(ranking.Order(), sorted);
  // Ranks are dense: equal values share one, each larger distinct value starts the next.
  std::vector<double> distinct(f.data(), f.data() + f.size());
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  for (Eigen::Index i = 0; i < f.cols(); ++i) {
    const auto expected = static_cast<std::size_t>(
        std::lower_bound(distinct.begin(), distinct.end(), f(0, i)) - distinct.begin());
    EXPECT_EQ(ranking.rank[static_cast<std::size_t>(i)], expected);
  }
}

TEST(ParetoTest, EmptySetHasNoRanks) {
  EXPECT_TRUE(RankPareto(Eigen::MatrixXd(2, 0)).Order().empty());
  EXPECT_TRUE(FirstFront(Eigen::MatrixXd(2, 0)).empty());
}

}  // namespace
}  // namespace evoslam
