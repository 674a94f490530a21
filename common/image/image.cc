#include "common/image/image.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// Rounds a pixel coordinate to the nearest pixel index, saturating far outside any image so that
// the conversion to int is always defined.
int RoundToPixel(double v) {
  constexpr double kLimit = 1 << 30;
  return static_cast<int>(std::lround(std::clamp(v, -kLimit, kLimit)));
}

// Clips the segment p0 + s * (p1 - p0), s in [0, 1], to the box [lo, hi] (Liang-Barsky).
// Returns false when nothing of it lies in the box. A clipped end is put exactly on the boundary
// it was clipped at, which interpolation alone would miss for very long segments.
bool ClipSegment(double& x0, double& y0, double& x1, double& y1, double lo_x, double lo_y,
                 double hi_x, double hi_y) {
  const double dx = x1 - x0;
  const double dy = y1 - y0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - lo_x, hi_x - x0, y0 - lo_y, hi_y - y0};
  const double bound[4] = {lo_x, hi_x, lo_y, hi_y};
  double s0 = 0.0;
  double s1 = 1.0;
  int c0 = -1;  // constraint that set s0, if any
  int c1 = -1;
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double s = q[i] / p[i];
    if (p[i] < 0.0 && s > s0) {
      s0 = s;
      c0 = i;
    } else if (p[i] > 0.0 && s < s1) {
      s1 = s;
      c1 = i;
    }
  }
  if (s0 > s1) return false;
  const auto end = [&](double s, int c, double& x, double& y) {
    x = c == 0 || c == 1 ? bound[c] : x0 + s * dx;
    y = c == 2 || c == 3 ? bound[c] : y0 + s * dy;
  };
  double nx0 = x0;
  double ny0 = y0;
  if (c0 >= 0) end(s0, c0, nx0, ny0);
  if (c1 >= 0) end(s1, c1, x1, y1);
  x0 = nx0;
  y0 = ny0;
  return true;
}

}  // namespace

Rgb Blend(Rgb from, Rgb to, double t) {
  t = std::clamp(t, 0.0, 1.0);
  const auto channel = [t](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + t * (b - a)));
  };
  return {channel(from.r, to.r), channel(from.g, to.g), channel(from.b, to.b)};
}

Image::Image(int width, int height, Rgb fill) : width_(width), height_(height) {
  if (width < 0 || height < 0) {
    throw Error("image size must not be negative, got " + std::to_string(width) + " x " +
                std::to_string(height));
  }
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

int CountPixels(const Image& image, Rgb color) {
  int n = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) n += image.at(x, y) == color;
  }
  return n;
}

void Image::SetPixel(int x, int y, Rgb color) {
  if (contains(x, y)) at(x, y) = color;
}

void Image::DrawLine(double x0, double y0, double x1, double y1, Rgb color, int thickness) {
  if (thickness < 1 || width_ == 0 || height_ == 0) return;
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) {
    return;
  }
  // The brush covers offsets [lo, hi] around each point of the line, so only points within that
  // reach of the image can colour anything; clipping first bounds the work by the image size.
  thickness = std::min(thickness, 1 << 24);  // keeps the int arithmetic below from overflowing
  const int lo = -(thickness - 1) / 2;
  const int hi = thickness / 2;
  if (!ClipSegment(x0, y0, x1, y1, -0.5 - hi, -0.5 - hi, width_ - 0.5 - lo, height_ - 0.5 - lo)) {
    return;
  }
  // Walk the major axis a pixel at a time, the minor coordinate rounded. The brush swept along
  // the line covers, in each major-axis line of pixels c, the stamps of the points a in
  // [c - hi, c - lo]; their minor coordinates are monotone with steps of at most one, so that
  // union is one run, and each pixel is written once however thick the brush.
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const double a0 = x_major ? x0 : y0;
  const double a1 = x_major ? x1 : y1;
  const double b0 = x_major ? y0 : x0;
  const double slope = a1 == a0 ? 0.0 : ((x_major ? y1 : x1) - b0) / (a1 - a0);
  const auto minor = [&](int a) { return RoundToPixel(b0 + (a - a0) * slope); };
  const int a_min = std::min(RoundToPixel(a0), RoundToPixel(a1));
  const int a_max = std::max(RoundToPixel(a0), RoundToPixel(a1));
  const int major_size = x_major ? width_ : height_;
  const int minor_size = x_major ? height_ : width_;
  for (int c = std::max(0, a_min + lo); c <= std::min(major_size - 1, a_max + hi); ++c) {
    const int first = std::max(a_min, c - hi);
    const int last = std::min(a_max, c - lo);
    if (first > last) continue;
    const int b_first = minor(first);
    const int b_last = minor(last);
    const int b_lo = std::max(0, std::min(b_first, b_last) + lo);
    const int b_hi = std::min(minor_size - 1, std::max(b_first, b_last) + hi);
    for (int b = b_lo; b <= b_hi; ++b) {
      if (x_major) {
        at(c, b) = color;
      } else {
        at(b, c) = color;
      }
    }
  }
}

void Image::DrawDisc(double cx, double cy, double radius, Rgb color) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !IsFiniteNonNegative(radius)) return;
  const double x_lo = std::max(0.0, std::ceil(cx - radius));
  const double x_hi = std::min(width_ - 1.0, std::floor(cx + radius));
  const double y_lo = std::max(0.0, std::ceil(cy - radius));
  const double y_hi = std::min(height_ - 1.0, std::floor(cy + radius));
  if (x_lo > x_hi || y_lo > y_hi) return;
  for (int y = static_cast<int>(y_lo); y <= static_cast<int>(y_hi); ++y) {
    for (int x = static_cast<int>(x_lo); x <= static_cast<int>(x_hi); ++x) {
      if (std::hypot(x - cx, y - cy) <= radius) at(x, y) = color;
    }
  }
}

void Image::FillRect(int x, int y, int width, int height, Rgb color) {
  // In 64 bits, so that a rectangle reaching past INT_MAX clips rather than overflows.
  const long long x_end = std::min<long long>(width_, static_cast<long long>(x) + width);
  const long long y_end = std::min<long long>(height_, static_cast<long long>(y) + height);
  for (long long py = std::max(0, y); py < y_end; ++py) {
    for (long long px = std::max(0, x); px < x_end; ++px) {
      at(static_cast<int>(px), static_cast<int>(py)) = color;
    }
  }
}

void Image::Paste(const Image& source, int x, int y) {
  const auto inside = [](long long v, int size) { return v >= 0 && v < size; };
  for (int sy = 0; sy < source.height(); ++sy) {
    const long long ty = static_cast<long long>(y) + sy;
    if (!inside(ty, height_)) continue;
    for (int sx = 0; sx < source.width(); ++sx) {
      const long long tx = static_cast<long long>(x) + sx;
      if (inside(tx, width_)) at(static_cast<int>(tx), static_cast<int>(ty)) = source.at(sx, sy);
    }
  }
}

}  // namespace evoslam
