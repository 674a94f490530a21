#include "common/localization/ray_fan.h"

#include <cmath>

namespace evoslam {

RayFan::RayFan(double first, double step_angle, std::size_t size)
    : first_angle(first), step(step_angle), dx(size), dy(size) {
  for (std::size_t i = 0; i < size; ++i) {
    const double a = first + static_cast<double>(i) * step_angle;
    dx[i] = static_cast<float>(std::cos(a));
    dy[i] = static_cast<float>(std::sin(a));
  }
}

void RayFan::RotatedInto(double angle, RayFan& out) const {
  out.first_angle = first_angle + angle;
  out.step = step;
  out.dx.resize(dx.size());
  out.dy.resize(dy.size());
  const auto c = static_cast<float>(std::cos(angle));
  const auto s = static_cast<float>(std::sin(angle));
  for (std::size_t i = 0; i < dx.size(); ++i) {
    out.dx[i] = c * dx[i] - s * dy[i];
    out.dy[i] = s * dx[i] + c * dy[i];
  }
}

}  // namespace evoslam
