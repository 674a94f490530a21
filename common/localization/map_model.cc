#include "common/localization/map_model.h"

#include "common/grid/map_io.h"
#include "common/localization/grid_renderer.h"
#include "common/localization/segment_renderer.h"

namespace evoslam {

std::unique_ptr<RangeRenderer> MapModel::LocalRenderer(const Eigen::Vector2d& center,
                                                       double radius) const {
  if (const LineMap* lines = walls()) {
    return std::make_unique<SegmentRenderer>(TemporaryMap(*lines, center, radius));
  }
  return std::make_unique<GridRenderer>(*grid());
}

MapModel LoadMapModel(const std::filesystem::path& path) {
  if (path.extension() == ".yaml" || path.extension() == ".yml") return MapModel(ReadMapYaml(path));
  return MapModel(ReadLineMap(path));
}

}  // namespace evoslam
