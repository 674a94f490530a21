#include "common/optim/binary_coding.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

#include "common/util/error.h"

namespace evoslam {
namespace {

// 003's localization window: 60 x 60 cm on a 1 cm grid.
BinaryCoding WindowCoding(int bits) {
  return BinaryCoding(Eigen::Vector2d(-0.3, -0.3), Eigen::Vector2d(0.3, 0.3), bits, 0.01);
}

TEST(BinaryCodingTest, RoundTripLandsOnTheNearestGridPoint) {
  const BinaryCoding coding = WindowCoding(16);
  Rng rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    const double x = rng.Uniform(-0.3, 0.3);
    const double decoded = coding.Decode(0, coding.Encode(0, x));
    const double nearest = -0.3 + std::round((x + 0.3) / 0.01) * 0.01;
    EXPECT_NEAR(decoded, nearest, 1e-12) << x;
    EXPECT_LE(std::abs(decoded - x), 0.005 + 1e-12) << x;
  }
}

TEST(BinaryCodingTest, ValuesOutsideTheBoxGoToItsEdge) {
  const BinaryCoding coding = WindowCoding(16);
  EXPECT_EQ(coding.Decode(1, coding.Encode(1, -7.0)), -0.3);
  EXPECT_NEAR(coding.Decode(1, coding.Encode(1, 7.0)), 0.3, 1e-12);
}

TEST(BinaryCodingTest, EveryCodeIsAGridPointInsideTheBoxAndEveryPointGetsAnEqualShare) {
  // The width is not a whole number of steps: the last grid point, 0.25, lies below the bound.
  const BinaryCoding coding(Eigen::VectorXd::Constant(1, 0.0), Eigen::VectorXd::Constant(1, 0.255),
                            10, 0.01);
  std::map<long, int> codes_per_point;
  for (std::uint32_t code = 0; code <= coding.max_code(); ++code) {
    const double v = coding.Decode(0, code);
    ASSERT_GE(v, 0.0);
    ASSERT_LE(v, 0.255);
    const double k = v / 0.01;
    ASSERT_NEAR(k, std::round(k), 1e-9) << code;
    ++codes_per_point[std::lround(k)];
    if (code > 0) {
      EXPECT_GE(v, coding.Decode(0, code - 1));  // monotone
    }
  }
  ASSERT_EQ(codes_per_point.size(), 26u);  // points 0..25, all reachable
  for (const auto& [point, count] : codes_per_point) {
    // 1024 codes over 26 points: 39 or 40 each.
    EXPECT_GE(count, 39) << point;
    EXPECT_LE(count, 40) << point;
  }
}

TEST(BinaryCodingTest, FewerCodesThanGridPointsSpreadOverTheWholeWindow) {
  const BinaryCoding coding = WindowCoding(3);  // 8 codes, 61 grid points
  EXPECT_EQ(coding.Decode(0, 0), -0.3);
  EXPECT_NEAR(coding.Decode(0, 7), 0.3, 1e-12);
  for (std::uint32_t code = 0; code <= 7; ++code) {
    const double v = coding.Decode(0, code);
    EXPECT_NEAR(v, -0.3 + std::round(code * 60.0 / 7.0) * 0.01, 1e-12);
    EXPECT_EQ(coding.Encode(0, v), code);
  }
  // A value between two codes' points goes to the nearer one.
  EXPECT_EQ(coding.Encode(0, coding.Decode(0, 2) + 0.02), 2u);
  EXPECT_EQ(coding.Encode(0, coding.Decode(0, 3) - 0.02), 3u);
}

TEST(BinaryCodingTest, WithoutGridCodesSpreadEvenlyOverTheBox) {
  const BinaryCoding coding(Eigen::Vector2d(-5.0, 1.0), Eigen::Vector2d(5.0, 2.0), 12, 0.0);
  EXPECT_EQ(coding.Decode(0, 0), -5.0);
  EXPECT_EQ(coding.Decode(0, 4095), 5.0);
  EXPECT_EQ(coding.Decode(1, 4095), 2.0);
  for (std::uint32_t code = 0; code <= 4095; ++code) {
    EXPECT_NEAR(coding.Decode(0, code), -5.0 + code * 10.0 / 4095.0, 1e-12);
    ASSERT_EQ(coding.Encode(0, coding.Decode(0, code)), code);
  }
  // Halfway between two codes' values, or nearer one of them.
  const double step = 10.0 / 4095.0;
  EXPECT_EQ(coding.Encode(0, coding.Decode(0, 100) + 0.4 * step), 100u);
  EXPECT_EQ(coding.Encode(0, coding.Decode(0, 100) + 0.6 * step), 101u);
}

TEST(BinaryCodingTest, DegenerateBoxHasOnePoint) {
  const BinaryCoding grid(Eigen::VectorXd::Constant(1, 2.0), Eigen::VectorXd::Constant(1, 2.0), 8,
                          0.5);
  const BinaryCoding plain(Eigen::VectorXd::Constant(1, 2.0), Eigen::VectorXd::Constant(1, 2.0), 8,
                           0.0);
  for (std::uint32_t code : {0u, 17u, 255u}) {
    EXPECT_EQ(grid.Decode(0, code), 2.0);
    EXPECT_EQ(plain.Decode(0, code), 2.0);
  }
  EXPECT_EQ(grid.Encode(0, 3.0), 0u);
  EXPECT_EQ(plain.Encode(0, 3.0), 0u);
}

TEST(BinaryCodingTest, RandomChromosomesDrawEveryCodeAlike) {
  const BinaryCoding coding(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(3), 2, 0.0);
  Rng rng(11);
  std::array<int, 4> counts{};
  constexpr int kDraws = 4000;
  for (int i = 0; i < kDraws; ++i) {
    const Chromosome c = coding.Random(rng);
    ASSERT_EQ(c.size(), 3);
    for (Eigen::Index j = 0; j < 3; ++j) {
      ASSERT_LE(c(j), 3u);
      ++counts[c(j)];
    }
  }
  // 3000 expected per code; five standard deviations is about 140.
  for (const int count : counts) EXPECT_NEAR(count, 3 * kDraws / 4, 150);
}

TEST(BinaryCodingTest, DecodeCandidatesConformsToTheEncoding) {
  class IntegerBox : public Problem {
   public:
    const Eigen::VectorXd& lower() const override { return lo_; }
    const Eigen::VectorXd& upper() const override { return hi_; }
    Encoding encoding() const override { return Encoding::kInteger; }
    void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>&, std::span<double>) const override {}

   private:
    Eigen::VectorXd lo_ = Eigen::VectorXd::Constant(1, -3.0);
    Eigen::VectorXd hi_ = Eigen::VectorXd::Constant(1, 3.0);
  };
  const IntegerBox problem;
  const BinaryCoding coding(problem.lower(), problem.upper(), 8, 0.0);
  Chromosomes chromosomes(1, 256);
  for (Eigen::Index i = 0; i < 256; ++i) chromosomes(0, i) = static_cast<std::uint32_t>(i);
  Eigen::MatrixXd x;
  DecodeCandidates(problem, coding, chromosomes, x);
  ASSERT_EQ(x.cols(), 256);
  for (Eigen::Index i = 0; i < 256; ++i) {
    EXPECT_EQ(x(0, i), std::round(coding.Decode(0, chromosomes(0, i))));
  }
}

TEST(BinaryCodingTest, ChromosomesSurviveACheckpoint) {
  Chromosomes c(2, 3);
  c << 0, 65535, 17, 1, 2, 40000;
  EXPECT_EQ(ChromosomesFromMemory(ChromosomesToMemory(c), 16, "x"), c);
  Eigen::MatrixXd bad = ChromosomesToMemory(c);
  bad(1, 1) = 2.5;
  EXPECT_THROW(ChromosomesFromMemory(bad, 16, "x"), Error);
  bad(1, 1) = -1.0;
  EXPECT_THROW(ChromosomesFromMemory(bad, 16, "x"), Error);
  bad(1, 1) = 65536.0;
  EXPECT_THROW(ChromosomesFromMemory(bad, 16, "x"), Error);
  EXPECT_NO_THROW(ChromosomesFromMemory(bad, 17, "x"));
}

TEST(BinaryCodingTest, RejectsImpossibleCodings) {
  const Eigen::Vector2d lo(0, 0), hi(1, 1);
  EXPECT_THROW(BinaryCoding(lo, hi, 0, 0.0), Error);
  EXPECT_THROW(BinaryCoding(lo, hi, 31, 0.0), Error);
  EXPECT_THROW(BinaryCoding(lo, hi, 16, -0.1), Error);
  EXPECT_THROW(BinaryCoding(lo, Eigen::Vector2d(1e300, 1), 16, 1e-300), Error);
  EXPECT_NO_THROW(BinaryCoding(lo, hi, 30, 1e-9));
}

}  // namespace
}  // namespace evoslam
