#ifndef EVOSLAM_COMMON_GRID_GRID_IMAGE_H_
#define EVOSLAM_COMMON_GRID_GRID_IMAGE_H_

#include <filesystem>

#include "common/grid/occupancy_grid.h"
#include "common/image/image.h"
#include "common/image/world_canvas.h"

namespace evoslam {

inline constexpr Rgb kOccupiedCellColor{0, 0, 0};
inline constexpr Rgb kFreeCellColor{255, 255, 255};
inline constexpr Rgb kUnknownCellColor{205, 205, 205};

// The grid with one pixel per cell, coloured by state; world y up is image row 0 at the top.
Image RenderGrid(const OccupancyGrid& grid);

// RenderGrid written as PNG; throws evoslam::Error naming the path on failure.
void WriteGridPng(const OccupancyGrid& grid, const std::filesystem::path& path);

// Paints every canvas pixel whose centre lies on the grid with the colour of that cell, so that
// trajectories can be drawn over a grid at the canvas's own scale.
void DrawGrid(const OccupancyGrid& grid, WorldCanvas& canvas);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_GRID_IMAGE_H_
