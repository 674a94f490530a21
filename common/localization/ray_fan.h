#ifndef EVOSLAM_COMMON_LOCALIZATION_RAY_FAN_H_
#define EVOSLAM_COMMON_LOCALIZATION_RAY_FAN_H_

#include <cstddef>
#include <vector>

namespace evoslam {

// Rays at evenly spaced world angles first_angle + i * step, i < size, with their unit
// directions precomputed once so that rendering a candidate pose needs no trigonometry per ray.
struct RayFan {
  double first_angle = 0.0;
  double step = 0.0;
  std::vector<float> dx;
  std::vector<float> dy;

  RayFan() = default;
  RayFan(double first_angle, double step, std::size_t size);

  std::size_t size() const { return dx.size(); }
  // The same fan turned by `angle`, written into `out` (reused to avoid allocation).
  void RotatedInto(double angle, RayFan& out) const;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_RAY_FAN_H_
