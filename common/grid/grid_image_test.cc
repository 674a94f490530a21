#include "common/grid/grid_image.h"

#include <gtest/gtest.h>

namespace evoslam {
namespace {

OccupancyGrid SmallGrid() {
  // Row 0 (bottom): occupied, free, unknown; row 1 (top): free, free, occupied.
  OccupancyGrid grid(0.5, {-1.0, 2.0}, 3, 2);
  grid.SetCell(0, 0, CellState::kOccupied);
  grid.SetCell(1, 0, CellState::kFree);
  grid.SetCell(0, 1, CellState::kFree);
  grid.SetCell(1, 1, CellState::kFree);
  grid.SetCell(2, 1, CellState::kOccupied);
  return grid;
}

TEST(GridImageTest, DrawGridPaintsCellsAtCanvasScale) {
  const OccupancyGrid grid = SmallGrid();
  // Four pixels per cell, one cell of margin around the grid.
  WorldCanvas canvas(grid.min_corner(), grid.max_corner(), 0.125, 0.5, {1, 2, 3});
  DrawGrid(grid, canvas);
  const Image& image = canvas.image();
  ASSERT_EQ(image.width(), 20);
  ASSERT_EQ(image.height(), 16);
  for (int py = 0; py < image.height(); ++py) {
    for (int px = 0; px < image.width(); ++px) {
      const int cx = px / 4 - 1;
      const int cy = (image.height() - 1 - py) / 4 - 1;
      Rgb expected{1, 2, 3};
      if (grid.Contains(cx, cy)) {
        expected = grid.state(cx, cy) == CellState::kOccupied ? kOccupiedCellColor
                   : grid.state(cx, cy) == CellState::kFree   ? kFreeCellColor
                                                              : kUnknownCellColor;
      }
      EXPECT_EQ(image.at(px, py), expected) << px << "," << py;
    }
  }
  EXPECT_NE(kOccupiedCellColor, kFreeCellColor);
  EXPECT_NE(kUnknownCellColor, kFreeCellColor);
  EXPECT_NE(kUnknownCellColor, kOccupiedCellColor);
}

// Zoomed out to four cells a pixel, a wall one cell thick stays whole, and free space shows free.
TEST(GridImageTest, APixelOverSeveralCellsShowsTheMostTellingOfThem) {
  OccupancyGrid grid(0.05, {0.0, 0.0}, 200, 200);
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 150; ++x)
      grid.SetCell(x, y, x == 101 ? CellState::kOccupied : CellState::kFree);
  }
  WorldCanvas canvas(grid.min_corner(), grid.max_corner(), 0.2, 0.0, {1, 2, 3});
  DrawGrid(grid, canvas);
  const Image& image = canvas.image();
  ASSERT_EQ(image.width(), 50);
  ASSERT_EQ(image.height(), 50);
  for (int py = 0; py < 50; ++py) {
    EXPECT_EQ(image.at(25, py), kOccupiedCellColor) << py;
    EXPECT_EQ(image.at(10, py), kFreeCellColor) << py;
    EXPECT_EQ(image.at(45, py), kUnknownCellColor) << py;
  }
  EXPECT_EQ(CountPixels(image, kOccupiedCellColor), 50);
}

}  // namespace
}  // namespace evoslam
