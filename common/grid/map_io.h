#ifndef EVOSLAM_COMMON_GRID_MAP_IO_H_
#define EVOSLAM_COMMON_GRID_MAP_IO_H_

#include <filesystem>
#include <istream>
#include <string>

#include "common/grid/occupancy_grid.h"

namespace evoslam {

// ROS map_server maps: a small YAML file
//   image: map.pgm            (relative paths are relative to the YAML's folder)
//   resolution: 0.05          (metres per pixel)
//   origin: [x, y, yaw]       (world pose of the lower-left pixel; yaw must be 0)
//   negate: 0
//   occupied_thresh: 0.65
//   free_thresh: 0.196
//   mode: trinary             (optional; "scale" reads the same, "raw" is not supported)
// and a PGM (P5 or P2) or PNG image whose top row is the map's top (largest y). A pixel of value
// v is occupied when p = (255 - v) / 255 (v / 255 when negated) exceeds occupied_thresh, free
// when p is below free_thresh, else unknown. Unknown keys are ignored.

// Loads a map as a grid whose cell states (OccupancyGrid::state) reproduce the file's, with the
// distance field built. Throws evoslam::InputError naming the file, and the line for YAML
// problems, on a missing or duplicate key, a bad value, or a missing or malformed image.
OccupancyGrid ReadMapYaml(const std::filesystem::path& yaml);

// The image a map YAML names, as written there (unquoted), read by ReadMapYaml's own parser;
// nothing else is read. Throws evoslam::InputError naming `source` as ReadMapYaml does.
std::string ReadMapYamlImageName(std::istream& yaml, const std::string& source);

// Writes `yaml` and, beside it, the image NAME.pgm for yaml NAME.yaml: occupied cells 0, free
// 254, unknown 205, with map_server's usual thresholds 0.65 and 0.196. Throws evoslam::Error
// naming the path on failure.
void WriteMapYaml(const OccupancyGrid& grid, const std::filesystem::path& yaml);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_MAP_IO_H_
