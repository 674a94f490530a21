#include "common/grid/grid_image.h"

#include <algorithm>
#include <cmath>

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

void DrawGrid(const OccupancyGrid& grid, WorldCanvas& canvas) {
  Image& image = canvas.image();
  const double half = canvas.metres_per_pixel() / 2;
  const bool pixels_span_cells = canvas.metres_per_pixel() > grid.resolution();
  // The first and last cells along one axis that the span [lo, hi) of world coordinates meets.
  const auto first = [&grid](double lo, double origin) {
    return static_cast<long long>(std::floor((lo - origin) / grid.resolution()));
  };
  const auto last = [&grid](double hi, double origin) {
    return static_cast<long long>(std::ceil((hi - origin) / grid.resolution())) - 1;
  };
  for (int py = 0; py < image.height(); ++py) {
    for (int px = 0; px < image.width(); ++px) {
      const Eigen::Vector2d centre = canvas.ToWorld({px, py});
      if (!pixels_span_cells) {
        if (const auto c = grid.WorldToCell(centre)) {
          image.at(px, py) = ColorOf(grid.state(c->x(), c->y()));
        }
        continue;
      }
      const long long x0 = std::max(0LL, first(centre.x() - half, grid.origin().x()));
      const long long x1 = std::min(grid.width() - 1LL, last(centre.x() + half, grid.origin().x()));
      const long long y0 = std::max(0LL, first(centre.y() - half, grid.origin().y()));
      const long long y1 =
          std::min(grid.height() - 1LL, last(centre.y() + half, grid.origin().y()));
      if (x0 > x1 || y0 > y1) continue;
      CellState strongest = CellState::kUnknown;
      for (long long y = y0; y <= y1 && strongest != CellState::kOccupied; ++y) {
        for (long long x = x0; x <= x1; ++x) {
          const CellState state = grid.state(static_cast<int>(x), static_cast<int>(y));
          if (state == CellState::kOccupied || state == CellState::kFree) strongest = state;
          if (state == CellState::kOccupied) break;
        }
      }
      image.at(px, py) = ColorOf(strongest);
    }
  }
}

}  // namespace evoslam
