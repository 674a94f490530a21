#ifndef EVOSLAM_COMMON_LOCALIZATION_GRID_RENDERER_H_
#define EVOSLAM_COMMON_LOCALIZATION_GRID_RENDERER_H_

#include "common/grid/occupancy_grid.h"
#include "common/localization/range_renderer.h"

namespace evoslam {

// Renders rays by casting each through an occupancy grid (whose ray casting skips free space with
// a distance field).
class GridRenderer : public RangeRenderer {
 public:
  explicit GridRenderer(const OccupancyGrid& grid) : grid_(grid) {}

  void Render(const Eigen::Vector2d& origin, const RayFan& fan, float max_range,
              std::span<float> ranges) const override;

 private:
  const OccupancyGrid& grid_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_GRID_RENDERER_H_
