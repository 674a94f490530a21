#include "common/grid/grid_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/util/error.h"
#include "common/util/infinity.h"

namespace evoslam {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(GridGeometryTest, RefusesGeometriesThatCannotBe) {
  const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  EXPECT_THROW(GridGeometry(0.0, zero, 4, 4), Error);
  EXPECT_THROW(GridGeometry(-0.5, zero, 4, 4), Error);
  EXPECT_THROW(GridGeometry(kNaN, zero, 4, 4), Error);
  EXPECT_THROW(GridGeometry(kInfinity, zero, 4, 4), Error);
  EXPECT_THROW(GridGeometry(0.5, Eigen::Vector2d(0.0, kNaN), 4, 4), Error);
  EXPECT_THROW(GridGeometry(0.5, Eigen::Vector2d(-kInfinity, 0.0), 4, 4), Error);
  EXPECT_THROW(GridGeometry(0.5, zero, 0, 4), Error);
  EXPECT_THROW(GridGeometry(0.5, zero, 4, -2), Error);
  EXPECT_NO_THROW(GridGeometry(0.5, zero, 1, 1));
}

TEST(GridGeometryTest, ADefaultGeometryHasNoCellsAndHoldsNoPoint) {
  const GridGeometry none;
  EXPECT_EQ(none.cell_count(), 0u);
  EXPECT_FALSE(none.Contains(0, 0));
  EXPECT_FALSE(none.WorldToCell(Eigen::Vector2d::Zero()));
  EXPECT_FALSE(none.CellIndex(Eigen::Vector2d(0.25, 0.25)));
}

TEST(GridGeometryTest, CellsCoverHalfOpenSquaresFromTheOrigin) {
  const GridGeometry grid(0.25, {1.0, -3.0}, 6, 3);
  EXPECT_EQ(grid.cell_count(), 18u);
  EXPECT_EQ(grid.max_corner(), Eigen::Vector2d(2.5, -2.25));
  // The lower and left edges belong to a cell, the upper and right ones to the next.
  EXPECT_EQ(grid.WorldToCell({1.0, -3.0}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(grid.WorldToCell({1.25, -2.75}), Eigen::Vector2i(1, 1));
  EXPECT_EQ(grid.WorldToCell({2.4999, -2.2501}), Eigen::Vector2i(5, 2));
  EXPECT_FALSE(grid.WorldToCell({2.5, -2.5}));
  EXPECT_FALSE(grid.WorldToCell({1.5, -2.25}));
  EXPECT_FALSE(grid.WorldToCell({0.9999, -2.5}));
  EXPECT_FALSE(grid.WorldToCell({1.5, -3.0001}));
  EXPECT_FALSE(grid.WorldToCell({kNaN, -2.5}));
  EXPECT_FALSE(grid.WorldToCell({1.5, -kInfinity}));
  EXPECT_FALSE(grid.WorldToCell({1e300, -2.5}));
  // Row by row from the lowest y.
  EXPECT_EQ(grid.Index(0, 0), 0u);
  EXPECT_EQ(grid.Index(5, 0), 5u);
  EXPECT_EQ(grid.Index(0, 1), 6u);
  EXPECT_EQ(grid.Index(5, 2), 17u);
  EXPECT_EQ(grid.CellIndex({2.4, -2.3}), 17u);
  EXPECT_FALSE(grid.CellIndex({2.6, -2.3}));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      EXPECT_TRUE(grid.Contains(x, y));
      const Eigen::Vector2d centre = grid.CellToWorld(x, y);
      EXPECT_EQ(centre, Eigen::Vector2d(1.125 + 0.25 * x, -2.875 + 0.25 * y));
      EXPECT_EQ(grid.WorldToCell(centre), Eigen::Vector2i(x, y));
    }
  }
  EXPECT_FALSE(grid.Contains(-1, 0));
  EXPECT_FALSE(grid.Contains(6, 0));
  EXPECT_FALSE(grid.Contains(0, 3));
}

TEST(GridGeometryTest, ContainsCellsAcceptsExactlyWhatFloorsIntoTheGrid) {
  const GridGeometry grid(0.1, Eigen::Vector2d::Zero(), 4, 2);
  EXPECT_TRUE(grid.ContainsCells(0.0, 0.0));
  EXPECT_TRUE(grid.ContainsCells(-0.0, 1.5));
  EXPECT_TRUE(grid.ContainsCells(std::nextafter(4.0, 0.0), std::nextafter(2.0, 0.0)));
  EXPECT_FALSE(grid.ContainsCells(4.0, 1.0));
  EXPECT_FALSE(grid.ContainsCells(1.0, 2.0));
  EXPECT_FALSE(grid.ContainsCells(std::nextafter(0.0, -1.0), 1.0));
  EXPECT_FALSE(grid.ContainsCells(kNaN, 1.0));
  EXPECT_FALSE(grid.ContainsCells(1.0, kNaN));
}

// The searches convert a point's coordinates one at a time and must find the cell WorldToCell
// finds, to the bit; WorldToCell must be the floor of the point in cells.
TEST(GridGeometryTest, EveryConversionAgreesWithTheFloorOfTheDivision) {
  const GridGeometry grid(0.06, {-7.3, 2.9}, 200, 150);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> x(-8.0, 6.0), y(1.0, 13.0);
  for (int i = 0; i < 10000; ++i) {
    const Eigen::Vector2d p(x(random), y(random));
    const Eigen::Vector2d cells = grid.ToCells(p);
    EXPECT_EQ(cells.x(), grid.CellX(p.x()));
    EXPECT_EQ(cells.y(), grid.CellY(p.y()));
    EXPECT_EQ(cells.x(), (p.x() - -7.3) / 0.06);
    const double fx = std::floor(cells.x()), fy = std::floor(cells.y());
    const bool inside = fx >= 0 && fy >= 0 && fx < 200 && fy < 150;
    const auto cell = grid.WorldToCell(p);
    ASSERT_EQ(cell.has_value(), inside) << p.transpose();
    EXPECT_EQ(grid.ContainsCells(cells.x(), cells.y()), inside);
    if (inside) {
      EXPECT_EQ(*cell, Eigen::Vector2i(static_cast<int>(fx), static_cast<int>(fy)));
      EXPECT_EQ(grid.CellIndex(p), grid.Index(cell->x(), cell->y()));
    }
  }
}

}  // namespace
}  // namespace evoslam
