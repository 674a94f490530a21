#ifndef EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_
#define EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "common/image/image.h"
#include "common/image/world_canvas.h"
#include "common/io/trajectory_io.h"
#include "common/localization/map_model.h"
#include "common/transform/pose2.h"

namespace evoslam {

// The pictures' colours, the same in every job's pictures.
inline constexpr Rgb kTruthColor{0, 160, 0};
inline constexpr Rgb kEstimateColor{220, 30, 30};

struct TrajectoryLayer {
  std::string name;
  std::vector<Pose2> poses;
  Rgb color;
};

// A trajectory's poses as a layer; the timestamps play no part in a picture.
TrajectoryLayer MakeLayer(std::string name, std::span<const StampedPose> trajectory, Rgb color);

// Draws the map (walls, or the grid's occupied and free cells) with trajectories on top, the
// first pose of each marked. The picture is scaled to about `max_pixels` on its longer side and
// covers the map and every pose of the layers.
WorldCanvas DrawMapPicture(const MapModel& map, std::span<const TrajectoryLayer> layers,
                           int max_pixels = 1600);

// DrawMapPicture written as PNG.
void WriteMapPicture(const MapModel& map, std::span<const TrajectoryLayer> layers,
                     const std::filesystem::path& path, int max_pixels = 1600);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_MAP_PICTURE_H_
