#include "common/grid/tiled_counts.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace evoslam {
namespace {

TEST(TiledCountsTest, HoldsWhatADenseArrayHoldsAndAllocatesOnlyTheTilesWithCounts) {
  // Sides that are not a whole number of tiles: the last row and column of tiles are partial.
  const int width = 3 * TiledCounts::kTileSide + 5, height = 2 * TiledCounts::kTileSide + 1;
  TiledCounts counts(width, height);
  std::vector<std::uint32_t> dense(static_cast<std::size_t>(width) * height, 0);
  const auto at = [&](int x, int y) -> std::uint32_t& {
    return dense[static_cast<std::size_t>(y) * width + x];
  };
  EXPECT_EQ(counts.tiles_allocated(), 0u);
  counts.set(width - 1, height - 1, 0);  // a zero allocates nothing
  EXPECT_EQ(counts.tiles_allocated(), 0u);
  counts.set(width - 1, height - 1, 7);
  at(width - 1, height - 1) = 7;
  counts.set(0, 0, 3);
  at(0, 0) = 3;
  EXPECT_EQ(counts.tiles_allocated(), 2u);
  EXPECT_EQ(counts.get(width - 1, height - 1), 7u);
  EXPECT_EQ(counts.get(width - 2, height - 1), 0u);

  // Changes in the first tile row only.
  std::mt19937 gen(5);
  std::uniform_int_distribution<int> x(0, width - 1), y(0, TiledCounts::kTileSide - 1);
  std::uniform_int_distribution<std::uint32_t> value(0, 4);
  for (int i = 0; i < 5000; ++i) {
    const int cx = x(gen), cy = y(gen);
    const std::uint32_t v = value(gen);
    counts.set(cx, cy, v);
    at(cx, cy) = v;
  }
  EXPECT_EQ(counts.tiles_allocated(), 5u);  // 4 in the first row, and the far corner's
  EXPECT_EQ(counts.bytes(),
            4 * 3 * sizeof(std::vector<std::uint32_t>) + 5 * TiledCounts::kTileCells * 4);
  for (int cy = 0; cy < height; ++cy) {
    for (int cx = 0; cx < width; ++cx)
      ASSERT_EQ(counts.get(cx, cy), at(cx, cy)) << cx << ", " << cy;
  }

  // Windows across tile borders, empty ones, and the whole grid.
  std::uniform_int_distribution<int> wx(0, width), wy(0, height);
  for (int i = 0; i < 200; ++i) {
    const int x0 = wx(gen), x1 = wx(gen), y0 = wy(gen), y1 = wy(gen);
    TiledCounts::Sums expected;
    for (int cy = y0; cy < y1; ++cy) {
      for (int cx = x0; cx < x1; ++cx) {
        expected.total += at(cx, cy);
        expected.nonzero += at(cx, cy) > 0;
      }
    }
    const TiledCounts::Sums sums = counts.Window(x0, y0, x1, y1);
    ASSERT_EQ(sums.total, expected.total) << x0 << " " << y0 << " " << x1 << " " << y1;
    ASSERT_EQ(sums.nonzero, expected.nonzero) << x0 << " " << y0 << " " << x1 << " " << y1;
  }
  const TiledCounts::Sums all = counts.Window(0, 0, width, height);
  EXPECT_EQ(all.total, counts.Window(0, 0, width, TiledCounts::kTileSide).total + 7);
}

TEST(TiledCountsTest, ACopyHoldsTheSameCountsApart) {
  TiledCounts counts(100, 100);
  counts.set(70, 10, 2);
  TiledCounts copy = counts;
  copy.set(70, 10, 5);
  EXPECT_EQ(counts.get(70, 10), 2u);
  EXPECT_EQ(copy.get(70, 10), 5u);
  EXPECT_EQ(copy.tiles_allocated(), 1u);
}

}  // namespace
}  // namespace evoslam
