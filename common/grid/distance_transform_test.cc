#include "common/grid/distance_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace evoslam {
namespace {

TEST(DistanceTransformTest, QuadrantVersionMatchesBruteForce) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 80; ++trial) {
    const int w = std::uniform_int_distribution<int>(1, 40)(rng);
    const int h = std::uniform_int_distribution<int>(1, 40)(rng);
    const double density = std::uniform_real_distribution<double>(0.0, 0.4)(rng);
    std::bernoulli_distribution seed(density);
    std::vector<std::uint8_t> seeds(static_cast<std::size_t>(w) * h);
    for (auto& s : seeds) s = seed(rng) ? 1 : 0;
    std::vector<double> d(seeds.size(), -1.0);
    SquaredQuadrantDistanceTransform(seeds, w, h, d);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        double best = std::numeric_limits<double>::infinity();
        for (int sy = y; sy < h; ++sy) {
          for (int sx = x; sx < w; ++sx) {
            if (seeds[static_cast<std::size_t>(sy) * w + sx] == 0) continue;
            best = std::min(best, static_cast<double>((x - sx) * (x - sx) + (y - sy) * (y - sy)));
          }
        }
        ASSERT_EQ(d[static_cast<std::size_t>(y) * w + x], best)
            << "trial " << trial << " cell " << x << "," << y;
      }
    }
  }
}

TEST(DistanceTransformTest, EmptyRasterIsInfinitelyFar) {
  const std::vector<std::uint8_t> seeds(12, 0);
  std::vector<double> out(12);
  SquaredQuadrantDistanceTransform(seeds, 4, 3, out);
  for (const double d : out) EXPECT_TRUE(std::isinf(d));
}

TEST(DistanceTransformTest, RejectsSizeMismatch) {
  const std::vector<std::uint8_t> seeds(5, 0);
  std::vector<double> out(4);
  EXPECT_THROW(SquaredQuadrantDistanceTransform(seeds, 2, 2, out), std::invalid_argument);
  const std::vector<std::uint8_t> four(4, 0);
  EXPECT_THROW(SquaredQuadrantDistanceTransform(four, 2, 2, std::span<double>(out).first(3)),
               std::invalid_argument);
}

}  // namespace
}  // namespace evoslam
