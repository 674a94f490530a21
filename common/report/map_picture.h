#ifndef EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_
#define EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "common/image/image.h"
#include "common/localization/map_model.h"
#include "common/transform/pose2.h"

namespace evoslam {

struct TrajectoryLayer {
  std::string name;
  std::vector<Pose2> poses;
  Rgb color;
};

// Draws the map (walls, or the grid's occupied and free cells) with trajectories on top, the
// first pose of each marked, and writes it as PNG. The picture is scaled to about `max_pixels`
// on its longer side.
void WriteMapPicture(const MapModel& map, std::span<const TrajectoryLayer> layers,
                     const std::filesystem::path& path, int max_pixels = 1600);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_
