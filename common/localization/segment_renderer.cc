#include "common/localization/segment_renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace evoslam {

SegmentRenderer::SegmentRenderer(std::span<const Segment> walls) {
  ax_.reserve(walls.size());
  ay_.reserve(walls.size());
  bx_.reserve(walls.size());
  by_.reserve(walls.size());
  for (const Segment& s : walls) {
    ax_.push_back(s.a.x());
    ay_.push_back(s.a.y());
    bx_.push_back(s.b.x());
    by_.push_back(s.b.y());
  }
}

void SegmentRenderer::Render(const Eigen::Vector2d& origin, const RayFan& fan, float max_range,
                             std::span<float> ranges) const {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const std::size_t n = fan.size();
  std::fill(ranges.begin(), ranges.begin() + static_cast<std::ptrdiff_t>(n), max_range);
  const double inv_step = 1.0 / fan.step;
  const double fan_end = fan.first_angle + static_cast<double>(n) * fan.step;

  for (std::size_t w = 0; w < ax_.size(); ++w) {
    const double p1x = ax_[w] - origin.x();
    const double p1y = ay_[w] - origin.y();
    const double ex = bx_[w] - ax_[w];
    const double ey = by_[w] - ay_[w];
    // Distance of the wall's line from the origin, scaled by the wall length; a wall seen
    // edge-on covers no ray.
    const double num = p1x * ey - p1y * ex;
    if (num == 0.0) continue;
    const double p2x = p1x + ex;
    const double p2y = p1y + ey;
    // The wall covers the angular interval from one end to the other, counter-clockwise from
    // the end that comes first in that direction (the arc is shorter than pi).
    const double phi1 = std::atan2(p1y, p1x);
    const double phi2 = std::atan2(p2y, p2x);
    // num = cross(p1, p2): positive when p1 -> p2 turns counter-clockwise.
    double start = num > 0.0 ? phi1 : phi2;
    double arc = (num > 0.0 ? phi2 : phi1) - start;
    if (arc < 0.0) arc += kTwoPi;
    // Express the start relative to the fan, in [-2pi, 0), then visit every turn of the circle
    // the fan covers: the first turn catches arcs that straddle the fan's first ray, and a fan
    // can be wider than 2pi when the heading window is wide.
    start = std::fmod(start - fan.first_angle, kTwoPi);
    if (start >= 0.0) start -= kTwoPi;
    const auto num_f = static_cast<float>(num);
    const auto ex_f = static_cast<float>(ex);
    const auto ey_f = static_cast<float>(ey);
    for (double turn = start; fan.first_angle + turn < fan_end; turn += kTwoPi) {
      const auto first =
          std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(std::ceil(turn * inv_step)));
      const auto last = std::min(static_cast<std::ptrdiff_t>(std::floor((turn + arc) * inv_step)),
                                 static_cast<std::ptrdiff_t>(n) - 1);
      for (std::ptrdiff_t i = first; i <= last; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        // Ray t*d meets the wall's line where t = cross(p1, e) / cross(d, e).
        const float denom = fan.dx[ui] * ey_f - fan.dy[ui] * ex_f;
        const float t = num_f / denom;
        if (t > 0.0f && t < ranges[ui]) ranges[ui] = t;
      }
    }
  }
}

std::vector<Segment> TemporaryMap(const LineMap& map, const Eigen::Vector2d& center,
                                  double radius) {
  std::vector<Segment> walls;
  const auto all = map.segments();
  for (std::size_t index : map.SegmentsNear(center, radius)) walls.push_back(all[index]);
  return walls;
}

}  // namespace evoslam
