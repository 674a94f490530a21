#include "common/image/marker.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// A quarter of the radius, and at least two pixels, so that a small ring still reads as one.
double StrokeWidth(double radius) { return std::max(2.0, radius / 4.0); }

void DrawRing(Image& image, double cx, double cy, double radius, Rgb color) {
  const double inner = radius - StrokeWidth(radius);
  const int x_lo = std::max(0, static_cast<int>(std::ceil(cx - radius)));
  const int x_hi = std::min(image.width() - 1, static_cast<int>(std::floor(cx + radius)));
  const int y_lo = std::max(0, static_cast<int>(std::ceil(cy - radius)));
  const int y_hi = std::min(image.height() - 1, static_cast<int>(std::floor(cy + radius)));
  for (int y = y_lo; y <= y_hi; ++y) {
    for (int x = x_lo; x <= x_hi; ++x) {
      const double d = std::hypot(x - cx, y - cy);
      if (d > inner && d <= radius) image.at(x, y) = color;
    }
  }
}

}  // namespace

void DrawMarker(Image& image, double x, double y, Marker marker, double radius, Rgb color) {
  // The bounds also keep the ring's pixel loop within int range.
  constexpr double kFar = 1 << 24;
  if (!std::isfinite(x) || !std::isfinite(y) || !IsFiniteNonNegative(radius) ||
      std::abs(x) > kFar || std::abs(y) > kFar || radius > kFar) {
    return;
  }
  switch (marker) {
    case Marker::kDot:
      image.DrawDisc(x, y, radius, color);
      return;
    case Marker::kRing:
      DrawRing(image, x, y, radius, color);
      return;
    case Marker::kCross: {
      // The arms' ends lie on the circle of the radius, less the brush's half width.
      const int thickness = static_cast<int>(std::lround(StrokeWidth(radius)));
      const double arm = std::max(0.0, (radius - thickness / 2.0) / std::numbers::sqrt2);
      image.DrawLine(x - arm, y - arm, x + arm, y + arm, color, thickness);
      image.DrawLine(x - arm, y + arm, x + arm, y - arm, color, thickness);
      return;
    }
  }
}

}  // namespace evoslam
