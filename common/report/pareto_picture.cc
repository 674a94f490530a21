#include "common/report/pareto_picture.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "common/image/bitmap_font.h"
#include "common/image/legend.h"
#include "common/image/marker.h"
#include "common/report/map_picture.h"
#include "common/report/pareto_fronts.h"

namespace evoslam {
namespace {

// Text at twice the font's size and bands padded by kParetoPad, as in the map pictures.
constexpr int kParetoTextScale = 2;
constexpr int kParetoPad = 16;
constexpr int kParetoMinWidth = 1000;
// A panel's size when several stand side by side; a lone panel spans the picture's width.
constexpr int kPanelWidth = 600;
constexpr int kPanelHeight = 560;
constexpr int kMostPanelColumns = 3;
// More fronts than this are told apart by the gradient, not each by a legend entry.
constexpr std::size_t kMostNamedFronts = 8;
// Marker radii, pixels.
constexpr double kMemberRadius = 4.0;
constexpr double kChosenRadius = 5.0;
constexpr double kChosenRingRadius = 9.0;
constexpr double kStartRadius = 9.0;
// The share of the values' span left clear beyond them on each axis, for the markers.
constexpr double kValueMargin = 0.06;
// The legend's gradient, pixels.
constexpr int kRampWidth = 200;
// The axes' grid lines, and the lines through the start, which part better from worse.
constexpr Rgb kParetoGridColor{230, 230, 230};
constexpr Rgb kParetoGuideColor{240, 185, 185};
// A bar of the one-objective picture takes this much of a front's width, and at most kWidestBar.
constexpr double kBarFill = 0.6;
constexpr int kWidestBar = 40;
constexpr int kBarStartThickness = 2;

// What the picture draws of one front: its values shown (relative or as they are) and its start.
class ShownFront {
 public:
  ShownFront(const ParetoFront& front, bool relative) : front_(front), relative_(relative) {}

  Eigen::Index members() const { return front_.f.cols(); }
  std::size_t chosen() const { return front_.chosen; }
  double value(Eigen::Index objective, Eigen::Index member) const {
    const double v = front_.f(objective, member);
    return relative_ ? RelativeToStart(v, front_.start[static_cast<std::size_t>(objective)]) : v;
  }
  bool finite(Eigen::Index member) const {
    for (Eigen::Index o = 0; o < front_.f.rows(); ++o) {
      if (!std::isfinite(value(o, member))) return false;
    }
    return true;
  }
  bool has_start() const { return !front_.start.empty(); }
  double start(Eigen::Index objective) const {
    return relative_ ? 1.0 : front_.start[static_cast<std::size_t>(objective)];
  }

 private:
  const ParetoFront& front_;
  bool relative_;
};

std::vector<ShownFront> Shown(std::span<const ParetoFront> fronts, bool relative) {
  std::vector<ShownFront> shown;
  for (const ParetoFront& f : fronts) shown.emplace_back(f, relative);
  return shown;
}

// The low and high end of some values; none yet while lo > hi.
struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// An axis of the values with a margin, [0, 1] when there are none.
PlotAxis AxisOf(const Extent& extent, std::string label) {
  if (extent.lo > extent.hi) return PaddedAxis(0.0, 1.0, 0.0, std::move(label));
  return PaddedAxis(extent.lo, extent.hi, kValueMargin, std::move(label));
}

std::string AxisLabel(const std::string& objective, bool relative) {
  return relative ? objective + ", relative to start" : objective;
}

// Members drawn: a scatter's have every objective finite, a bar's chosen value is finite.
std::size_t LeftOut(std::span<const ShownFront> fronts, bool one_objective) {
  std::size_t out = 0;
  for (const ShownFront& f : fronts) {
    if (one_objective) {
      out += !std::isfinite(f.value(0, static_cast<Eigen::Index>(f.chosen())));
      continue;
    }
    for (Eigen::Index m = 0; m < f.members(); ++m) out += !f.finite(m);
  }
  return out;
}

// What the picture shows, under the run's title.
std::string Description(std::span<const ParetoFront> fronts, bool relative) {
  const std::size_t n = fronts.size();
  const std::string searches = fmt::format("{} search{}", n, n == 1 ? "" : "es");
  const bool one = fronts.front().objectives.size() == 1;
  std::string text = one ? fmt::format("{} of the member chosen in each of {}",
                                       fronts.front().objectives[0], searches)
                         : fmt::format("Pareto front{} of {}", n == 1 ? "" : "s", searches);
  if (relative) text += ", relative to where each started (1)";
  return text + ": lower is better";
}

// A line of its own, so that the count is never broken across lines; empty when none is left out.
std::string LeftOutNote(std::size_t left_out, bool one_objective) {
  if (left_out == 0) return "";
  const char* what = one_objective ? (left_out == 1 ? "search" : "searches")
                                   : (left_out == 1 ? "member" : "members");
  return fmt::format("{} {} left out, not finite", left_out, what);
}

std::string FrontLabel(const ParetoFront& front, std::size_t index) {
  return front.label.empty() ? fmt::format("front {}", index) : front.label;
}

// Two or more objectives: the first against each other one, every x axis the same.
std::vector<PlotAxes> ScatterAxes(std::span<const ParetoFront> fronts,
                                  std::span<const ShownFront> shown, bool relative, int top,
                                  int width) {
  const Eigen::Index objectives = static_cast<Eigen::Index>(fronts.front().objectives.size());
  const int panels = static_cast<int>(objectives) - 1;
  const int columns = std::min(panels, kMostPanelColumns);
  const int panel_width = (width - (columns + 1) * kParetoPad) / columns;
  std::vector<Extent> extents(static_cast<std::size_t>(objectives));
  for (const ShownFront& f : shown) {
    for (Eigen::Index o = 0; o < objectives; ++o) {
      Extent& e = extents[static_cast<std::size_t>(o)];
      for (Eigen::Index m = 0; m < f.members(); ++m) e.Add(f.value(o, m));
      if (f.has_start()) e.Add(f.start(o));
    }
  }
  const std::vector<std::string>& names = fronts.front().objectives;
  std::vector<PlotAxes> axes;
  for (int k = 0; k < panels; ++k) {
    const Eigen::Vector2i corner(kParetoPad + (k % columns) * (panel_width + kParetoPad),
                                 top + (k / columns) * (kPanelHeight + kParetoPad));
    axes.emplace_back(corner, Eigen::Vector2i(panel_width, kPanelHeight),
                      AxisOf(extents[0], AxisLabel(names[0], relative)),
                      AxisOf(extents[static_cast<std::size_t>(k) + 1],
                             AxisLabel(names[static_cast<std::size_t>(k) + 1], relative)),
                      kParetoTextScale);
  }
  return axes;
}

// The lines through the start, in the plot area, where a relative picture has one start for all.
void DrawGuides(Image& image, const PlotAxes& axes) {
  const Eigen::Vector2d at = axes.ToPixel({1.0, 1.0});
  const Eigen::Vector2i& a = axes.area_top_left();
  const Eigen::Vector2i& n = axes.area_size();
  if (axes.y().min <= 1.0 && 1.0 <= axes.y().max) {
    image.DrawLine(a.x(), at.y(), a.x() + n.x() - 1, at.y(), kParetoGuideColor);
  }
  if (axes.x().min <= 1.0 && 1.0 <= axes.x().max) {
    image.DrawLine(at.x(), a.y(), at.x(), a.y() + n.y() - 1, kParetoGuideColor);
  }
}

// Panel k: every front's members, then each chosen one ringed, then the starts over them all.
void DrawScatter(Image& image, const PlotAxes& axes, Eigen::Index k,
                 std::span<const ShownFront> shown, bool relative) {
  if (relative) DrawGuides(image, axes);
  const auto pixel = [&](const ShownFront& f, Eigen::Index m) {
    return axes.ToPixel({f.value(0, m), f.value(k, m)});
  };
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const Rgb color = ParetoFrontColor(i, shown.size());
    for (Eigen::Index m = 0; m < shown[i].members(); ++m) {
      if (!shown[i].finite(m)) continue;
      const Eigen::Vector2d p = pixel(shown[i], m);
      DrawMarker(image, p.x(), p.y(), Marker::kDot, kMemberRadius, color);
    }
  }
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const auto chosen = static_cast<Eigen::Index>(shown[i].chosen());
    if (!shown[i].finite(chosen)) continue;
    const Eigen::Vector2d p = pixel(shown[i], chosen);
    DrawMarker(image, p.x(), p.y(), Marker::kDot, kChosenRadius, ParetoFrontColor(i, shown.size()));
    DrawMarker(image, p.x(), p.y(), Marker::kRing, kChosenRingRadius, kInkColor);
  }
  for (const ShownFront& f : shown) {
    if (!f.has_start()) continue;
    const Eigen::Vector2d p = axes.ToPixel({f.start(0), f.start(k)});
    DrawMarker(image, p.x(), p.y(), Marker::kCross, kStartRadius, kParetoStartColor);
    if (relative) break;  // every front's start is (1, 1)
  }
}

// One objective: the fronts' indices across, their chosen values up.
PlotAxes StripAxes(std::span<const ParetoFront> fronts, std::span<const ShownFront> shown,
                   bool relative, int top, int width) {
  Extent values;
  for (const ShownFront& f : shown) {
    values.Add(f.value(0, static_cast<Eigen::Index>(f.chosen())));
    if (f.has_start()) values.Add(f.start(0));
  }
  const double last = static_cast<double>(fronts.size()) - 1.0;
  return PlotAxes({kParetoPad, top}, {width - 2 * kParetoPad, kPanelHeight},
                  PlotAxis{-0.5, last + 0.5, "front, in the order the searches ran", true},
                  AxisOf(values, AxisLabel(fronts.front().objectives[0], relative)),
                  kParetoTextScale);
}

void DrawStrip(Image& image, const PlotAxes& axes, std::span<const ShownFront> shown,
               bool relative) {
  const double per_front = axes.area_size().x() / static_cast<double>(shown.size());
  const int bar = std::clamp(static_cast<int>(kBarFill * per_front), 1, kWidestBar);
  const double one = axes.ToPixel({0.0, 1.0}).y();
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const ShownFront& f = shown[i];
    const double value = f.value(0, static_cast<Eigen::Index>(f.chosen()));
    if (!std::isfinite(value)) continue;
    const Eigen::Vector2d at = axes.ToPixel({static_cast<double>(i), value});
    if (!relative) {
      DrawMarker(image, at.x(), at.y(), Marker::kDot, kChosenRadius, kParetoBetterColor);
      if (f.has_start()) {
        const Eigen::Vector2d start = axes.ToPixel({static_cast<double>(i), f.start(0)});
        DrawMarker(image, start.x(), start.y(), Marker::kCross, kStartRadius, kParetoStartColor);
      }
      continue;
    }
    const int left = static_cast<int>(std::lround(at.x() - (bar - 1) / 2.0));
    const int from = static_cast<int>(std::lround(std::min(at.y(), one)));
    const int to = static_cast<int>(std::lround(std::max(at.y(), one)));
    image.FillRect(left, from, bar, to - from + 1,
                   value < 1.0 ? kParetoBetterColor : kParetoWorseColor);
  }
  if (relative) {
    const Eigen::Vector2i& a = axes.area_top_left();
    image.DrawLine(a.x(), one, a.x() + axes.area_size().x() - 1, one, kParetoStartColor,
                   kBarStartThickness);
  }
}

std::vector<LegendEntry> ParetoLegend(std::span<const ParetoFront> fronts, bool relative) {
  const bool any_start = relative || std::ranges::any_of(fronts, [](const ParetoFront& f) {
                           return !f.start.empty();
                         });
  std::vector<LegendEntry> entries;
  if (fronts.front().objectives.size() == 1) {
    if (relative) {
      entries.push_back({"ended lower than it started", kParetoBetterColor, LegendMark::kSwatch});
      entries.push_back({"ended higher", kParetoWorseColor, LegendMark::kSwatch});
      entries.push_back(
          {"where each search started", kParetoStartColor, LegendMark::kLine, kBarStartThickness});
      return entries;
    }
    entries.push_back({"the member chosen", kParetoBetterColor, LegendMark::kDot});
  } else {
    if (fronts.size() <= kMostNamedFronts) {
      for (std::size_t i = 0; i < fronts.size(); ++i) {
        entries.push_back(
            {FrontLabel(fronts[i], i), ParetoFrontColor(i, fronts.size()), LegendMark::kDot});
      }
    }
    entries.push_back({"the member chosen", kInkColor, LegendMark::kRing});
  }
  if (any_start) {
    entries.push_back({"where each search started", kParetoStartColor, LegendMark::kCross});
  }
  return entries;
}

// The gradient of many fronts' colours between the first front's label and the last's, in a row
// that fits `width`: the labels give way to the fronts' indices where they would not fit.
class Ramp {
 public:
  Ramp(std::span<const ParetoFront> fronts, int width) {
    const std::size_t last = fronts.size() - 1;
    first_ = FrontLabel(fronts.front(), 0);
    last_ = FrontLabel(fronts.back(), last);
    if (Width() > width) {
      first_ = "front 0";
      last_ = fmt::format("front {}", last);
    }
  }

  void Draw(Image& image, int x, int y) const {
    const int s = kParetoTextScale;
    const int gap = kParetoPad / 2;
    DrawText(image, x, y, kLead, kInkColor, s);
    x += TextWidth(kLead, s) + 2 * gap;
    DrawText(image, x, y, first_, kInkColor, s);
    x += TextWidth(first_, s) + gap;
    // As tall as the capitals, outlined like the legend's swatches.
    const int height = 7 * s;
    image.FillRect(x, y, kRampWidth, height, kInkColor);
    for (int i = 1; i < kRampWidth - 1; ++i) {
      const Rgb color = ParetoFrontColor(static_cast<std::size_t>(i - 1),
                                         static_cast<std::size_t>(kRampWidth - 2));
      image.FillRect(x + i, y + 1, 1, height - 2, color);
    }
    DrawText(image, x + kRampWidth + gap, y, last_, kInkColor, s);
  }

  int Width() const {
    const int s = kParetoTextScale;
    return TextWidth(kLead, s) + TextWidth(first_, s) + kRampWidth + TextWidth(last_, s) +
           4 * (kParetoPad / 2);
  }

 private:
  static constexpr std::string_view kLead = "fronts in order:";
  std::string first_;
  std::string last_;
};

}  // namespace

Rgb ParetoFrontColor(std::size_t front, std::size_t fronts) {
  // Viridis up to its green: its yellow would fade into the white paper.
  static constexpr std::array<Rgb, 4> kStops = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}}};
  const double t = fronts < 2 ? 0.5 : static_cast<double>(front) / static_cast<double>(fronts - 1);
  const double along = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(along), kStops.size() - 2);
  return Blend(kStops[i], kStops[i + 1], along - static_cast<double>(i));
}

ParetoPicture DrawParetoPicture(std::span<const ParetoFront> fronts, std::string_view run_title) {
  CheckParetoFronts(fronts);
  const bool relative = DrawnRelativeToStart(fronts);
  const bool one_objective = fronts.front().objectives.size() == 1;
  const std::vector<ShownFront> shown = Shown(fronts, relative);

  const int panels = one_objective ? 1 : static_cast<int>(fronts.front().objectives.size()) - 1;
  const int columns = std::min(panels, kMostPanelColumns);
  const int rows = (panels + columns - 1) / columns;
  const int width = std::max(kParetoMinWidth, columns * kPanelWidth + (columns + 1) * kParetoPad);
  const int inner = width - 2 * kParetoPad;
  const int line = kLineAdvance * kParetoTextScale;

  std::vector<std::string> title;
  if (!run_title.empty()) title = WrapText(run_title, inner, kParetoTextScale);
  for (std::string& l : WrapText(Description(fronts, relative), inner, kParetoTextScale)) {
    title.push_back(std::move(l));
  }
  if (std::string note = LeftOutNote(LeftOut(shown, one_objective), one_objective); !note.empty()) {
    title.push_back(std::move(note));
  }
  const int panels_top = kParetoPad + static_cast<int>(title.size()) * line + kParetoPad;

  ParetoPicture picture{.image = {}, .panels = {}, .relative = relative};
  if (one_objective) {
    picture.panels.push_back(StripAxes(fronts, shown, relative, panels_top, width));
  } else {
    picture.panels = ScatterAxes(fronts, shown, relative, panels_top, width);
  }

  const bool ramp = !one_objective && fronts.size() > kMostNamedFronts;
  const std::vector<LegendEntry> entries = ParetoLegend(fronts, relative);
  const int legend_top = panels_top + rows * (kPanelHeight + kParetoPad);
  const int entries_top = legend_top + (ramp ? line + kParetoPad / 2 : 0);
  const int height = entries_top + LegendHeight(entries, inner, kParetoTextScale) + kParetoPad;

  picture.image = Image(width, height, kWhite);
  Image& image = picture.image;
  for (std::size_t i = 0; i < title.size(); ++i) {
    DrawText(image, kParetoPad, kParetoPad + static_cast<int>(i) * line, title[i], kInkColor,
             kParetoTextScale);
  }
  for (std::size_t k = 0; k < picture.panels.size(); ++k) {
    const PlotAxes& axes = picture.panels[k];
    axes.Draw(image, kInkColor, kParetoGridColor);
    if (one_objective) {
      DrawStrip(image, axes, shown, relative);
    } else {
      DrawScatter(image, axes, static_cast<Eigen::Index>(k) + 1, shown, relative);
    }
  }
  if (ramp) Ramp(fronts, inner).Draw(image, kParetoPad, legend_top);
  DrawLegend(image, kParetoPad, entries_top, inner, entries, kInkColor, kParetoTextScale);
  return picture;
}

void WriteParetoPicture(std::span<const ParetoFront> fronts, std::string_view run_title,
                        const std::filesystem::path& path) {
  WritePng(DrawParetoPicture(fronts, run_title).image, path);
}

}  // namespace evoslam
