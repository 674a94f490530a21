#include "common/image/scale_bar.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/image/bitmap_font.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Gap between the label and the ticks, the ticks' height above the bar and the bar's thickness,
// in font pixels.
constexpr int kLabelGap = 1;
constexpr int kTickHeight = 3;
constexpr int kBarThickness = 2;

}  // namespace

ScaleBar MakeScaleBar(double metres_per_pixel, int max_pixels) {
  if (!std::isfinite(metres_per_pixel) || metres_per_pixel <= 0.0 || max_pixels < 1) {
    throw Error(fmt::format("scale bar: needs positive metres per pixel and pixels, got {} and {}",
                            metres_per_pixel, max_pixels));
  }
  const double longest = metres_per_pixel * max_pixels;
  const double power = std::pow(10.0, std::floor(std::log10(longest)));
  double metres = power;
  for (const double step : {5.0, 2.0}) {
    if (step * power <= longest) {
      metres = step * power;
      break;
    }
  }
  const int pixels =
      std::clamp(static_cast<int>(std::lround(metres / metres_per_pixel)), 1, max_pixels);
  return {metres, pixels, fmt::format("{:g} m", metres)};
}

Eigen::Vector2i ScaleBarSize(const ScaleBar& bar, int scale) {
  return {std::max(bar.pixels, TextWidth(bar.label, scale)),
          TextHeight(scale) + (kLabelGap + kTickHeight + kBarThickness) * scale};
}

void DrawScaleBar(Image& image, int x, int y, const ScaleBar& bar, Rgb color, int scale) {
  const Eigen::Vector2i size = ScaleBarSize(bar, scale);
  DrawText(image, x + (size.x() - TextWidth(bar.label, scale)) / 2, y, bar.label, color, scale);
  const int left = x + (size.x() - bar.pixels) / 2;
  const int bar_top = y + size.y() - kBarThickness * scale;
  const int tick_top = bar_top - kTickHeight * scale;
  image.FillRect(left, bar_top, bar.pixels, kBarThickness * scale, color);
  image.FillRect(left, tick_top, scale, kTickHeight * scale, color);
  image.FillRect(left + bar.pixels - scale, tick_top, scale, kTickHeight * scale, color);
}

}  // namespace evoslam
