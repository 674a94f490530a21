#include "common/sim/noise_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/util/error.h"

namespace evoslam {
namespace {

struct Stats {
  double mean = 0.0;
  double sigma = 0.0;
  double min = 1e9;
  double max = -1e9;
};

// Statistics of reading - range over n readings of a beam with true range `range`.
Stats Residuals(const NoiseModel& noise, double range, int n) {
  Rng rng(5);
  Stats s;
  double sum = 0.0;
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = NoisyRange(range, 8.0, noise, rng) - range;
    sum += r;
    sum2 += r * r;
    s.min = std::min(s.min, r);
    s.max = std::max(s.max, r);
  }
  s.mean = sum / n;
  s.sigma = std::sqrt(sum2 / n - s.mean * s.mean);
  return s;
}

TEST(NoiseModelTest, NoNoiseKeepsRanges) {
  Rng rng(1);
  const NoiseModel none;
  EXPECT_EQ(NoisyRange(3.25, 8.0, none, rng), 3.25);
  EXPECT_EQ(NoisyRange(8.0, 8.0, none, rng), 8.0);
}

TEST(NoiseModelTest, UniformNoiseHasItsBandwidth) {
  const double b = 0.4;
  const Stats s = Residuals({.uniform_bandwidth = b}, 4.0, 100000);
  EXPECT_NEAR(s.mean, 0.0, 0.003);
  EXPECT_GE(s.min, -b / 2);
  EXPECT_LE(s.max, b / 2);
  EXPECT_GT(s.max - s.min, 0.99 * b);
  EXPECT_NEAR(s.sigma, b / std::sqrt(12.0), 0.02 * b / std::sqrt(12.0));
}

TEST(NoiseModelTest, GaussianNoiseHasItsSigma) {
  const Stats s = Residuals({.gaussian_sigma = 0.05}, 4.0, 100000);
  EXPECT_NEAR(s.mean, 0.0, 0.001);
  EXPECT_NEAR(s.sigma, 0.05, 0.001);
}

TEST(NoiseModelTest, QuantizationRoundsToTheStep) {
  Rng rng(2);
  const NoiseModel noise{.gaussian_sigma = 0.1, .quantization = 0.01};
  for (int i = 0; i < 1000; ++i) {
    const double r = NoisyRange(2.0, 8.0, noise, rng);
    EXPECT_NEAR(r / 0.01, std::round(r / 0.01), 1e-6);
  }
  Rng rng2(2);
  EXPECT_NEAR(NoisyRange(2.3456, 8.0, {.quantization = 0.01}, rng2), 2.35, 1e-12);
}

TEST(NoiseModelTest, ReadingsAreClampedAndNonReturnsUntouched) {
  Rng rng(3);
  const NoiseModel noise{.uniform_bandwidth = 2.0};
  bool hit_zero = false;
  bool hit_max = false;
  for (int i = 0; i < 1000; ++i) {
    const double low = NoisyRange(0.1, 8.0, noise, rng);
    const double high = NoisyRange(7.9, 8.0, noise, rng);
    EXPECT_GE(low, 0.0);
    EXPECT_LE(high, 8.0);
    hit_zero = hit_zero || low == 0.0;
    hit_max = hit_max || high == 8.0;
    EXPECT_EQ(NoisyRange(8.0, 8.0, noise, rng), 8.0);
  }
  EXPECT_TRUE(hit_zero);
  EXPECT_TRUE(hit_max);
}

TEST(NoiseModelTest, OdometryIncrementBiasAndNoise) {
  Rng rng(4);
  const Pose2 step(0.1, 0.0, 0.2);
  const Pose2 exact = NoisyOdometryIncrement(step, {0, 0, 0, 0}, rng);
  EXPECT_NEAR(exact.x(), 0.1, 1e-15);
  EXPECT_NEAR(exact.theta(), 0.2, 1e-15);
  // Bias alone: 2 % longer and 0.1 rad per metre more turn.
  const Pose2 biased = NoisyOdometryIncrement(step, {0, 0, 0.02, 0.1}, rng);
  EXPECT_NEAR(biased.x(), 0.102, 1e-12);
  EXPECT_NEAR(biased.theta(), 0.2 + 0.01, 1e-12);
  // Noise alone: relative spread of the translation as asked.
  double sum = 0.0;
  double sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double x = NoisyOdometryIncrement(step, {0.05, 0, 0, 0}, rng).x() / 0.1 - 1.0;
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.05, 0.002);
}

TEST(NoiseModelTest, RejectsBadParameters) {
  EXPECT_NO_THROW(CheckNoiseModel({}));
  EXPECT_THROW(CheckNoiseModel({.uniform_bandwidth = -1}), Error);
  EXPECT_THROW(CheckNoiseModel({.gaussian_sigma = std::nan("")}), Error);
  EXPECT_THROW(CheckNoiseModel({.quantization = -0.01}), Error);
  EXPECT_THROW(CheckNoiseModel({.pedestrians = -1}), Error);
  EXPECT_THROW(CheckNoiseModel({.pedestrian_radius = 0}), Error);
  NoiseModel bad_odometry;
  bad_odometry.odometry.rotation_bias = INFINITY;
  EXPECT_THROW(CheckNoiseModel(bad_odometry), Error);
}

}  // namespace
}  // namespace evoslam
