#include "common/grid/grid_image.h"

namespace evoslam {
namespace {

Rgb ColorOf(CellState state) {
  switch (state) {
    case CellState::kOccupied:
      return kOccupiedCellColor;
    case CellState::kFree:
      return kFreeCellColor;
    case CellState::kUnknown:
      break;
  }
  return kUnknownCellColor;
}

}  // namespace

Image RenderGrid(const OccupancyGrid& grid) {
  Image image(grid.width(), grid.height());
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      image.at(x, grid.height() - 1 - y) = ColorOf(grid.state(x, y));
    }
  }
  return image;
}

void WriteGridPng(const OccupancyGrid& grid, const std::filesystem::path& path) {
  WritePng(RenderGrid(grid), path);
}

void DrawGrid(const OccupancyGrid& grid, WorldCanvas& canvas) {
  Image& image = canvas.image();
  for (int py = 0; py < image.height(); ++py) {
    for (int px = 0; px < image.width(); ++px) {
      const auto cell = grid.WorldToCell(canvas.ToWorld({px, py}));
      if (cell) image.at(px, py) = ColorOf(grid.state(cell->x(), cell->y()));
    }
  }
}

}  // namespace evoslam
