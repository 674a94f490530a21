#ifndef EVOSLAM_COMMON_LOCALIZATION_MAP_MODEL_H_
#define EVOSLAM_COMMON_LOCALIZATION_MAP_MODEL_H_

#include <filesystem>
#include <memory>
#include <variant>

#include "common/grid/occupancy_grid.h"
#include "common/line_map/line_map.h"
#include "common/localization/range_renderer.h"

namespace evoslam {

// The known map a robot localizes in: walls (LineMap) or an occupancy grid.
class MapModel {
 public:
  explicit MapModel(LineMap walls) : map_(std::move(walls)) {}
  explicit MapModel(OccupancyGrid grid) : map_(std::move(grid)) {}

  // A renderer for rays from anywhere within `radius` of `center` (plus the rays' range): the
  // temporary map of the walls around the robot, or the grid itself.
  std::unique_ptr<RangeRenderer> LocalRenderer(const Eigen::Vector2d& center, double radius) const;

  const LineMap* walls() const { return std::get_if<LineMap>(&map_); }
  const OccupancyGrid* grid() const { return std::get_if<OccupancyGrid>(&map_); }

 private:
  std::variant<LineMap, OccupancyGrid> map_;
};

// Reads a LineMap text file, or a ROS map_server grid when the path ends in .yaml.
MapModel LoadMapModel(const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_MAP_MODEL_H_
