#include "common/localization/map_model.h"

#include "common/grid/map_io.h"
#include "common/localization/grid_renderer.h"
#include "common/localization/segment_renderer.h"
#include "common/util/error.h"

namespace evoslam {

std::unique_ptr<RangeRenderer> MapModel::LocalRenderer(const Eigen::Vector2d& center,
                                                       double radius) const {
  if (const LineMap* lines = walls()) {
    return std::make_unique<SegmentRenderer>(TemporaryMap(*lines, center, radius));
  }
  return std::make_unique<GridRenderer>(*grid());
}

namespace {

bool HasOccupiedCell(const OccupancyGrid& grid) {
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      if (grid.IsOccupied(x, y)) return true;
    }
  }
  return false;
}

}  // namespace

MapModel LoadMapModel(const std::filesystem::path& path) {
  // Every beam of a map without walls reads its maximum range wherever the robot stands, so a
  // localization in it would "succeed" with a trajectory that means nothing.
  if (path.extension() == ".yaml" || path.extension() == ".yml") {
    OccupancyGrid grid = ReadMapYaml(path);
    if (!HasOccupiedCell(grid)) throw InputError(path.string(), 0, "the map has no occupied cell");
    return MapModel(std::move(grid));
  }
  LineMap walls = ReadLineMap(path);
  if (walls.empty()) throw InputError(path.string(), 0, "the map has no walls");
  return MapModel(std::move(walls));
}

}  // namespace evoslam
