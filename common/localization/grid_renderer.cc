#include "common/localization/grid_renderer.h"

#include <algorithm>

namespace evoslam {

void GridRenderer::Render(const Eigen::Vector2d& origin, const RayFan& fan, float max_range,
                          std::span<float> ranges) const {
  for (std::size_t i = 0; i < fan.size(); ++i) {
    const Eigen::Vector2d direction(fan.dx[i], fan.dy[i]);
    const double r = grid_.CastRay(origin, direction, max_range);
    ranges[i] = std::min(static_cast<float>(r), max_range);
  }
}

}  // namespace evoslam
