#ifndef EVOSLAM_COMMON_REPORT_PARETO_PICTURE_H_
#define EVOSLAM_COMMON_REPORT_PARETO_PICTURE_H_

#include <cstddef>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "common/image/image.h"
#include "common/image/plot_axes.h"
#include "common/slam/slam_method.h"

namespace evoslam {

// The colours of the Pareto picture besides the fronts' (ParetoFrontColor); its words, axes and
// the ring around each chosen member are in kInkColor (map_picture.h).
inline constexpr Rgb kParetoStartColor{220, 30, 30};
// A search of one objective that ended below its start, or above it.
inline constexpr Rgb kParetoBetterColor{33, 145, 140};
inline constexpr Rgb kParetoWorseColor{240, 140, 0};

// Front `front` of `fronts`, by its place along a gradient from dark violet (the first) through
// blue and teal to green (the last), so that many fronts read as an order; a lone front is teal.
Rgb ParetoFrontColor(std::size_t front, std::size_t fronts);

// The picture of the fronts, and where it put its plots, to find a value's pixel by.
struct ParetoPicture {
  Image image;
  // Two or more objectives: panel k plots the first objective (x) against objective k + 1 (y),
  // up to three panels a row. One objective: one panel of each front's chosen value (y) against
  // the front's index (x).
  std::vector<PlotAxes> panels;
  bool relative = false;  // the values drawn are RelativeToStart's (pareto_fronts.h)
};

// A title (the run's, then what the picture shows), the panels, and under them a legend.
// Values are drawn relative to where each search started when DrawnRelativeToStart, so that a
// value of 1 is where a search started and the start is marked at (1, 1); else as they are, with
// each front's start, when known, marked. Two or more objectives: each front's members as dots in
// the front's colour, its chosen member larger and ringed; the legend names each front, or for
// more than 8 shows the gradient from the first front's label to the last's. One objective: a bar
// per front from 1 to its chosen member's value, teal where it ended lower and orange where
// higher; drawn as they are, a dot at the chosen value and a cross at the start when known.
// Non-finite values are left out and the title counts them. Throws Error as CheckParetoFronts does.
ParetoPicture DrawParetoPicture(std::span<const ParetoFront> fronts, std::string_view run_title);

// DrawParetoPicture's image written as PNG; throws Error naming the path on failure.
void WriteParetoPicture(std::span<const ParetoFront> fronts, std::string_view run_title,
                        const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_PARETO_PICTURE_H_
