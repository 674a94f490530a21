#include "common/image/plot_axes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/image/bitmap_font.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// In font pixels: a tick's length outside the frame, and the gap between a tick and its number
// and between the numbers and an axis's name.
constexpr int kTickLength = 3;
constexpr int kAxisGap = 4;
constexpr int kMinAreaPixels = 20;
// Fixed-point numbers with more decimals than this read worse than an exponent.
constexpr int kMaxDecimals = 8;

void CheckAxis(const PlotAxis& axis) {
  if (!std::isfinite(axis.min) || !std::isfinite(axis.max) || !(axis.min < axis.max) ||
      !std::isfinite(axis.max - axis.min)) {
    throw Error(fmt::format("plot axis '{}': needs finite values with min below max, got {} to {}",
                            axis.label, axis.min, axis.max));
  }
}

int Floor10(double v) { return static_cast<int>(std::floor(std::log10(v) + 1e-9)); }

std::vector<std::string> TickTexts(const std::vector<double>& values, double step) {
  double largest = 0.0;
  for (const double v : values) largest = std::max(largest, std::abs(v));
  const int decimals = std::max(0, -Floor10(step));
  std::vector<std::string> texts;
  for (const double v : values) {
    if (largest < 1e6 && decimals <= kMaxDecimals) {
      texts.push_back(fmt::format("{:.{}f}", v, decimals));
    } else if (v == 0.0) {
      texts.emplace_back("0");
    } else {
      // The digits from the value's first down to the step's.
      const int digits = std::clamp(Floor10(std::max(std::abs(v), step)) - Floor10(step) + 1, 1,
                                    std::numeric_limits<double>::max_digits10);
      texts.push_back(fmt::format("{:.{}e}", v, digits - 1));
    }
  }
  return texts;
}

int WidestText(const std::vector<std::string>& texts, int scale) {
  int widest = 0;
  for (const std::string& t : texts) widest = std::max(widest, TextWidth(t, scale));
  return widest;
}

int RoundPixel(double v) { return static_cast<int>(std::lround(v)); }

}  // namespace

PlotAxis PaddedAxis(double lo, double hi, double fraction, std::string label, bool whole) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi || !IsFiniteNonNegative(fraction)) {
    throw Error(
        fmt::format("plot axis '{}': needs finite values from low to high and a padding of at "
                    "least 0, got {} to {} and {}",
                    label, lo, hi, fraction));
  }
  double pad = fraction * (hi - lo);
  if (lo == hi) pad = lo == 0.0 ? 0.5 : 0.05 * std::abs(lo);
  PlotAxis axis{lo - pad, hi + pad, std::move(label), whole};
  CheckAxis(axis);
  return axis;
}

PlotTicks MakePlotTicks(const PlotAxis& axis, int max_ticks) {
  CheckAxis(axis);
  if (max_ticks < 1) throw Error(fmt::format("plot axis '{}': needs room for a tick", axis.label));
  const double span = axis.max - axis.min;
  // The step grows until the ticks are few enough; one wider than the span leaves one at most.
  double power = std::max(std::pow(10.0, std::floor(std::log10(span / max_ticks))),
                          std::numeric_limits<double>::min());
  for (;; power *= 10.0) {
    for (const double multiple : {1.0, 2.0, 5.0}) {
      const double step = multiple * power;
      if (axis.whole && step < 1.0) continue;
      const double first = std::ceil(axis.min / step);
      const double last = std::floor(axis.max / step);
      if (last - first + 1.0 > max_ticks) continue;
      PlotTicks ticks{.step = step, .values = {}, .texts = {}};
      // Counted, since past 2^53 adding one to a double may leave it as it was.
      const auto count = static_cast<long long>(last - first) + 1;
      for (long long i = 0; i < count; ++i) ticks.values.push_back((first + i) * step);
      ticks.texts = TickTexts(ticks.values, step);
      return ticks;
    }
  }
}

PlotAxes::PlotAxes(const Eigen::Vector2i& top_left, const Eigen::Vector2i& size, PlotAxis x,
                   PlotAxis y, int text_scale)
    : x_(std::move(x)), y_(std::move(y)), text_scale_(text_scale), top_left_(top_left) {
  if (text_scale < 1) throw Error(fmt::format("plot: text scale {} is below 1", text_scale));
  const int line = TextHeight(text_scale);
  const int gap = kAxisGap * text_scale;
  const int tick = kTickLength * text_scale;
  // Over the area the y axis's name; under it the frame, the ticks, their numbers and the x
  // axis's name. The frame is a pixel outside the area on each side.
  const int top = line + gap + 1;
  const int height = size.y() - top - (1 + tick + gap + line + gap + line);
  const int fit_y = std::max(1, height / (3 * line));
  y_ticks_ = MakePlotTicks(y_, fit_y);
  const int left = WidestText(y_ticks_.texts, text_scale) + gap + tick + 1;
  // The x ticks' numbers set how many fit across, and half the last one's reaches past the area.
  const int room = size.x() - left - 1;
  int fit_x = std::max(1, room / (6 * line));
  for (;; --fit_x) {
    x_ticks_ = MakePlotTicks(x_, fit_x);
    const int pitch = WidestText(x_ticks_.texts, text_scale) + 3 * gap;
    if (fit_x == 1 || static_cast<int>(x_ticks_.values.size()) * pitch <= room) break;
  }
  const int right = std::max(gap, WidestText(x_ticks_.texts, text_scale) / 2);
  area_top_left_ = top_left + Eigen::Vector2i(left, top);
  area_size_ = {room - right, height};
  if (area_size_.minCoeff() < kMinAreaPixels) {
    throw Error(fmt::format("plot: {} x {} pixels leave no room for a plot of '{}' against '{}'",
                            size.x(), size.y(), y_.label, x_.label));
  }
}

Eigen::Vector2d PlotAxes::ToPixel(const Eigen::Vector2d& value) const {
  const double u = (value.x() - x_.min) / (x_.max - x_.min);
  const double v = (y_.max - value.y()) / (y_.max - y_.min);
  return {area_top_left_.x() + u * (area_size_.x() - 1),
          area_top_left_.y() + v * (area_size_.y() - 1)};
}

void PlotAxes::Draw(Image& image, Rgb ink, Rgb grid) const {
  const int s = text_scale_;
  const int gap = kAxisGap * s;
  const int tick = kTickLength * s;
  const int stroke = std::max(1, s / 2);
  const Eigen::Vector2i& a = area_top_left_;
  const Eigen::Vector2i& n = area_size_;
  const int below = a.y() + n.y() + 1;  // the first row under the frame
  for (std::size_t i = 0; i < x_ticks_.values.size(); ++i) {
    const int px = RoundPixel(ToPixel({x_ticks_.values[i], y_.min}).x());
    image.FillRect(px, a.y(), 1, n.y(), grid);
    image.FillRect(px - (stroke - 1) / 2, below, stroke, tick, ink);
    const std::string& text = x_ticks_.texts[i];
    DrawText(image, px - TextWidth(text, s) / 2, below + tick + gap, text, ink, s);
  }
  for (std::size_t i = 0; i < y_ticks_.values.size(); ++i) {
    const int py = RoundPixel(ToPixel({x_.min, y_ticks_.values[i]}).y());
    image.FillRect(a.x(), py, n.x(), 1, grid);
    image.FillRect(a.x() - 1 - tick, py - (stroke - 1) / 2, tick, stroke, ink);
    const std::string& text = y_ticks_.texts[i];
    DrawText(image, a.x() - 1 - tick - gap - TextWidth(text, s), py - (kCapitalHeight * s - 1) / 2,
             text, ink, s);
  }
  image.FillRect(a.x() - 1, a.y() - 1, n.x() + 2, 1, ink);
  image.FillRect(a.x() - 1, a.y() + n.y(), n.x() + 2, 1, ink);
  image.FillRect(a.x() - 1, a.y(), 1, n.y(), ink);
  image.FillRect(a.x() + n.x(), a.y(), 1, n.y(), ink);
  const int name_top = below + tick + gap + TextHeight(s) + gap;
  DrawText(image, a.x() + (n.x() - TextWidth(x_.label, s)) / 2, name_top, x_.label, ink, s);
  DrawText(image, top_left_.x(), top_left_.y(), y_.label, ink, s);
}

}  // namespace evoslam
