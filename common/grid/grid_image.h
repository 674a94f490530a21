#ifndef EVOSLAM_COMMON_GRID_GRID_IMAGE_H_
#define EVOSLAM_COMMON_GRID_GRID_IMAGE_H_

#include "common/grid/occupancy_grid.h"
#include "common/image/image.h"
#include "common/image/world_canvas.h"

namespace evoslam {

inline constexpr Rgb kOccupiedCellColor{0, 0, 0};
inline constexpr Rgb kFreeCellColor{255, 255, 255};
inline constexpr Rgb kUnknownCellColor{205, 205, 205};

// Paints the canvas pixels over the grid with the colours of its cells, so that trajectories can
// be drawn over a grid at the canvas's own scale. A pixel no larger than a cell takes the colour
// of the cell its centre lies in; a larger one, that of the most telling cell it covers
// (occupied, else free, else unknown), so that walls a cell thick stay whole in a picture of a
// large map.
void DrawGrid(const OccupancyGrid& grid, WorldCanvas& canvas);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_GRID_IMAGE_H_
