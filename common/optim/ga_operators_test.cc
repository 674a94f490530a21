#include "common/optim/ga_operators.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace evoslam {
namespace {

constexpr int kBits = 16;

// The chromosome as one string of 0/1, coordinate 0's most significant bit first.
std::vector<int> BitString(const Chromosome& c) {
  std::vector<int> out;
  for (Eigen::Index j = 0; j < c.size(); ++j) {
    for (int k = kBits - 1; k >= 0; --k) out.push_back(static_cast<int>((c(j) >> k) & 1u));
  }
  return out;
}

Chromosome RandomChromosome(Eigen::Index dim, Rng& rng) {
  Chromosome c(dim);
  for (Eigen::Index j = 0; j < dim; ++j) c(j) = static_cast<std::uint32_t>(rng.UniformIndex(65536));
  return c;
}

TEST(GaOperatorsTest, CrossoverChildrenShareOutTheParentsBits) {
  Rng rng(3);
  for (const GaCrossover kind : {GaCrossover::kTwoPoint, GaCrossover::kUniform}) {
    for (int trial = 0; trial < 200; ++trial) {
      const Chromosome a = RandomChromosome(3, rng);
      const Chromosome b = RandomChromosome(3, rng);
      Chromosome ca(3), cb(3);
      CrossChromosomes(kind, kBits, a, b, rng, ca, cb);
      for (Eigen::Index j = 0; j < 3; ++j) {
        // Where the parents agree the children do too; elsewhere each child has one parent's bit.
        EXPECT_EQ(ca(j) & cb(j), a(j) & b(j));
        EXPECT_EQ(ca(j) ^ cb(j), a(j) ^ b(j));
        EXPECT_LT(ca(j), 65536u);
        EXPECT_LT(cb(j), 65536u);
      }
    }
  }
}

TEST(GaOperatorsTest, TwoPointCrossoverExchangesOneRunOfBitsAtRandomPlaces) {
  // All-zero and all-one parents show the exchanged bits as the ones of child_a.
  const Chromosome zeros = Chromosome::Zero(2);
  const Chromosome ones = Chromosome::Constant(2, 65535u);
  Rng rng(8);
  std::set<int> starts, ends;
  double exchanged = 0.0;
  constexpr int kTrials = 3000;
  for (int trial = 0; trial < kTrials; ++trial) {
    Chromosome ca(2), cb(2);
    CrossChromosomes(GaCrossover::kTwoPoint, kBits, zeros, ones, rng, ca, cb);
    const std::vector<int> s = BitString(ca);
    int first = -1, last = -1, runs = 0;
    for (int p = 0; p < 32; ++p) {
      if (s[p] == 1 && (p == 0 || s[p - 1] == 0)) {
        ++runs;
        first = p;
      }
      if (s[p] == 1) last = p;
    }
    ASSERT_EQ(runs, 1) << "two cut points exchange one contiguous run";
    starts.insert(first);
    ends.insert(last);
    exchanged += static_cast<double>(last - first + 1);
    EXPECT_EQ(cb, (ones.array() - ca.array()).matrix());
  }
  EXPECT_EQ(starts.size(), 31u);  // every boundary but the end of the string is a first cut
  EXPECT_EQ(ends.size(), 31u);
  // Two distinct cuts among 32 boundaries: on average 11 bits between them.
  EXPECT_NEAR(exchanged / kTrials, 11.0, 0.5);
}

TEST(GaOperatorsTest, UniformCrossoverExchangesEachBitWithProbabilityOneHalf) {
  const Chromosome zeros = Chromosome::Zero(2);
  const Chromosome ones = Chromosome::Constant(2, 65535u);
  Rng rng(9);
  std::vector<int> per_bit(32, 0);
  constexpr int kTrials = 4000;
  for (int trial = 0; trial < kTrials; ++trial) {
    Chromosome ca(2), cb(2);
    CrossChromosomes(GaCrossover::kUniform, kBits, zeros, ones, rng, ca, cb);
    const std::vector<int> s = BitString(ca);
    for (int p = 0; p < 32; ++p) per_bit[p] += s[p];
  }
  // Each bit: 2000 expected, standard deviation about 32.
  for (int p = 0; p < 32; ++p) EXPECT_NEAR(per_bit[p], kTrials / 2, 160) << p;
}

TEST(GaOperatorsTest, OneBitStringsCannotBeCut) {
  const Chromosome a = Chromosome::Zero(1);
  const Chromosome b = Chromosome::Ones(1);
  Chromosome ca(1), cb(1);
  Rng rng(1);
  CrossChromosomes(GaCrossover::kTwoPoint, 1, a, b, rng, ca, cb);
  EXPECT_EQ(ca, a);
  EXPECT_EQ(cb, b);
}

TEST(GaOperatorsTest, MutantsFillTheBoxAroundTheBest) {
  Chromosome best(2);
  best << 30000u, 100u;  // the second code sits near the bottom of the range
  const std::uint32_t max_code = 65535;
  const auto half = static_cast<std::int64_t>(std::llround(0.05 * max_code));
  Rng rng(4);
  std::int64_t lowest[2] = {max_code, max_code}, highest[2] = {0, 0};
  double mean0 = 0.0;
  constexpr int kTrials = 4000;
  for (int trial = 0; trial < kTrials; ++trial) {
    Chromosome m(2);
    MutateNearBest(best, max_code, 0.05, rng, m);
    for (int j = 0; j < 2; ++j) {
      lowest[j] = std::min<std::int64_t>(lowest[j], m(j));
      highest[j] = std::max<std::int64_t>(highest[j], m(j));
    }
    mean0 += m(0);
  }
  // The first coordinate spans the box on both sides of the best; the second is cut at code 0.
  EXPECT_GE(lowest[0], 30000 - half);
  EXPECT_LE(highest[0], 30000 + half);
  EXPECT_LT(lowest[0], 30000 - 0.95 * half);
  EXPECT_GT(highest[0], 30000 + 0.95 * half);
  EXPECT_NEAR(mean0 / kTrials, 30000.0, 0.05 * half);
  EXPECT_EQ(lowest[1], 0);
  EXPECT_LE(highest[1], 100 + half);
  EXPECT_GT(highest[1], 100 + 0.95 * half);
}

TEST(GaOperatorsTest, RankingPutsBestFirstAndNanLast) {
  Eigen::MatrixXd f(1, 6);
  f << 3.0, std::numeric_limits<double>::quiet_NaN(), 1.0, 3.0, -2.0, 0.5;
  EXPECT_EQ(RankByFitness(f), (std::vector<std::size_t>{4, 5, 2, 0, 3, 1}));
}

TEST(GaOperatorsTest, MatesAreTwoDistinctMembersOfThePool) {
  const std::vector<std::size_t> ranking = {7, 3, 5, 0, 1, 2, 4, 6};
  Rng rng(6);
  std::set<std::size_t> seen;
  for (int trial = 0; trial < 500; ++trial) {
    const auto [a, b] = DrawMates(ranking, 3, rng);
    EXPECT_NE(a, b);
    seen.insert(a);
    seen.insert(b);
  }
  EXPECT_EQ(seen, (std::set<std::size_t>{7, 3, 5}));
}

TEST(GaOperatorsTest, BestCandidatesReplaceTheWorstIndividuals) {
  const std::vector<std::size_t> ranking = {2, 0, 3, 1};  // population, best first
  Eigen::MatrixXd candidate_f(1, 5);
  candidate_f << 9.0, 1.0, 5.0, 0.5, 7.0;
  const auto moves = ReplaceWorst(ranking, candidate_f, 2);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[0], (std::pair<std::size_t, std::size_t>{1, 3}));
  EXPECT_EQ(moves[1], (std::pair<std::size_t, std::size_t>{3, 1}));
}

TEST(GaOperatorsTest, BitFlipsHitEachBitWithTheGivenProbability) {
  // 3 codes of 10 bits, flipped 20 000 times with p = 0.1: every bit flips close to 2000 times,
  // and never a bit above the 10th.
  Rng rng(6);
  std::vector<int> flips(30, 0);
  for (int trial = 0; trial < 20000; ++trial) {
    Chromosome c = Chromosome::Zero(3);
    FlipBits(10, 0.1, rng, c);
    for (Eigen::Index j = 0; j < 3; ++j) {
      EXPECT_LT(c(j), 1u << 10);
      for (int b = 0; b < 10; ++b) flips[static_cast<std::size_t>(j * 10 + b)] += (c(j) >> b) & 1u;
    }
  }
  for (const int f : flips) EXPECT_NEAR(f, 2000, 200);
  Chromosome untouched = Chromosome::Constant(3, 5);
  FlipBits(10, 0.0, rng, untouched);
  EXPECT_EQ(untouched, Chromosome::Constant(3, 5));
}

}  // namespace
}  // namespace evoslam
