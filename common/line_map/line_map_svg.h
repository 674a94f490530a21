#ifndef EVOSLAM_COMMON_LINE_MAP_LINE_MAP_SVG_H_
#define EVOSLAM_COMMON_LINE_MAP_LINE_MAP_SVG_H_

#include <Eigen/Core>
#include <filesystem>
#include <span>
#include <vector>

#include "common/line_map/line_map.h"

namespace evoslam {

// Writes the map's walls in black and each polyline (e.g. a trajectory) in its own colour from
// a small palette, as an SVG drawing with the world's y axis pointing up. One SVG user unit is
// one metre scaled by pixels_per_metre. Throws evoslam::Error naming the path on failure.
void WriteSvg(const LineMap& map, const std::filesystem::path& path,
              std::span<const std::vector<Eigen::Vector2d>> polylines = {},
              double pixels_per_metre = 50.0);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LINE_MAP_LINE_MAP_SVG_H_
