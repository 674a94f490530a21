#ifndef EVOSLAM_COMMON_LOCALIZATION_RANGE_RENDERER_H_
#define EVOSLAM_COMMON_LOCALIZATION_RANGE_RENDERER_H_

#include <Eigen/Core>
#include <span>

#include "common/localization/ray_fan.h"

namespace evoslam {

// Simulates the ranges a laser at `origin` would measure along every ray of a fan. A ray that
// meets nothing within max_range reads exactly max_range. Implementations are immutable after
// construction, so one renderer serves all threads.
class RangeRenderer {
 public:
  virtual ~RangeRenderer() = default;
  virtual void Render(const Eigen::Vector2d& origin, const RayFan& fan, float max_range,
                      std::span<float> ranges) const = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_RANGE_RENDERER_H_
