#include "common/report/map_picture.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "common/grid/grid_image.h"
#include "common/image/bitmap_font.h"
#include "common/image/legend.h"
#include "common/image/scale_bar.h"
#include "common/image/world_canvas.h"

namespace evoslam {
namespace {

// Text is drawn at twice the font's size; the bands around the map area are padded by kPad.
constexpr int kTextScale = 2;
constexpr int kPad = 16;
// The picture is at least this wide, so that the title and legend fit beside a narrow map.
constexpr int kMinPictureWidth = 1000;
// The map area's outline.
constexpr Rgb kFrameColor{150, 150, 150};

struct LayerStyle {
  Rgb color;
  int thickness;  // pixels
  bool frames;    // whether the map area grows to hold it; else it is clipped at the frame
};

LayerStyle StyleOf(LayerKind kind) {
  switch (kind) {
    case LayerKind::kOdometry:
      return {kOdometryColor, 2, false};
    case LayerKind::kTruth:
      return {kTruthColor, 7, true};
    case LayerKind::kCompared:
      return {kComparedColor, 4, true};
    case LayerKind::kEstimate:
      break;
  }
  return {kEstimateColor, 2, true};
}

// Grows `bounds` to hold `p`.
void Include(std::optional<Bounds>& bounds, const Eigen::Vector2d& p) {
  if (!bounds) {
    bounds = Bounds{p, p};
    return;
  }
  bounds->min = bounds->min.cwiseMin(p);
  bounds->max = bounds->max.cwiseMax(p);
}

// The first and last index whose count, with those before (after) it, exceeds `skip`.
std::pair<int, int> Span(const std::vector<long long>& counts, long long skip) {
  std::size_t lo = 0;
  long long seen = counts[lo];
  while (seen <= skip) seen += counts[++lo];
  std::size_t hi = counts.size() - 1;
  seen = counts[hi];
  while (seen <= skip) seen += counts[--hi];
  return {static_cast<int>(lo), static_cast<int>(hi)};
}

// Where a grid's map is: its occupied cells, less the 0.5 % most outlying on each side along
// each axis, so that a few stray returns do not set the frame (beams that pass windows and doors
// leave free streaks far out, and are not the map either); when none is occupied, the cells it
// has seen; when it has seen none, the whole grid.
Bounds MapBounds(const OccupancyGrid& grid) {
  std::vector<long long> columns(static_cast<std::size_t>(grid.width()), 0);
  std::vector<long long> rows(static_cast<std::size_t>(grid.height()), 0);
  long long occupied = 0;
  Eigen::Vector2i lo(grid.width(), grid.height());
  Eigen::Vector2i hi(-1, -1);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const CellState state = grid.state(x, y);
      if (state == CellState::kUnknown) continue;
      lo = lo.cwiseMin(Eigen::Vector2i(x, y));
      hi = hi.cwiseMax(Eigen::Vector2i(x, y));
      if (state != CellState::kOccupied) continue;
      ++columns[static_cast<std::size_t>(x)];
      ++rows[static_cast<std::size_t>(y)];
      ++occupied;
    }
  }
  if (hi.x() < 0) return {grid.min_corner(), grid.max_corner()};
  if (occupied > 0) {
    const long long skip = occupied / 200;
    std::tie(lo.x(), hi.x()) = Span(columns, skip);
    std::tie(lo.y(), hi.y()) = Span(rows, skip);
  }
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(grid.resolution() / 2);
  return {grid.CellToWorld(lo.x(), lo.y()) - half, grid.CellToWorld(hi.x(), hi.y()) + half};
}

Bounds FrameBounds(const MapModel& map, const MapPictureContent& content) {
  std::optional<Bounds> bounds;
  if (const LineMap* walls = map.walls(); walls && !walls->empty()) {
    Include(bounds, walls->bounds().min);
    Include(bounds, walls->bounds().max);
  } else if (const OccupancyGrid* grid = map.grid()) {
    const Bounds walls = MapBounds(*grid);
    Include(bounds, walls.min);
    Include(bounds, walls.max);
  }
  for (const TrajectoryLayer& layer : content.layers) {
    if (!StyleOf(layer.kind).frames) continue;
    for (const Pose2& p : layer.poses) Include(bounds, p.translation());
  }
  return bounds.value_or(Bounds{{0.0, 0.0}, {1.0, 1.0}});
}

// The map with the layers and loops, framed as DrawMapPicture says.
WorldCanvas DrawMapArea(const MapModel& map, const MapPictureContent& content) {
  const Bounds bounds = FrameBounds(map, content);
  const Eigen::Vector2d size = bounds.max - bounds.min;
  const double extent = std::max({size.x(), size.y(), 1.0});
  const double margin = 0.03 * extent;
  WorldCanvas canvas(bounds.min, bounds.max, (extent + 2 * margin) / kMapAreaPixels, margin,
                     map.grid() ? kUnknownCellColor : kWhite);
  if (const LineMap* walls = map.walls()) {
    for (const Segment& s : walls->segments()) canvas.DrawSegment(s.a, s.b, kOccupiedCellColor, 2);
  } else if (const OccupancyGrid* grid = map.grid()) {
    DrawGrid(*grid, canvas);
  }
  std::vector<const TrajectoryLayer*> layers;
  for (const TrajectoryLayer& layer : content.layers) layers.push_back(&layer);
  std::stable_sort(layers.begin(), layers.end(),
                   [](const auto* a, const auto* b) { return a->kind < b->kind; });
  for (const TrajectoryLayer* layer : layers) {
    if (layer->poses.empty()) continue;
    const LayerStyle style = StyleOf(layer->kind);
    std::vector<Eigen::Vector2d> points;
    points.reserve(layer->poses.size());
    for (const Pose2& p : layer->poses) points.push_back(p.translation());
    canvas.DrawPolyline(points, style.color, style.thickness);
    canvas.DrawPose(layer->poses.front(), style.color, 4.0 + style.thickness / 2.0, 2);
  }
  for (const LoopLink& loop : content.loops) {
    canvas.DrawSegment(loop.earlier, loop.later, kLoopColor, 2);
    canvas.DrawPoint(loop.earlier, 4.0, kLoopColor);
    canvas.DrawPoint(loop.later, 4.0, kLoopColor);
  }
  return canvas;
}

// The layers from the most telling down, the loops, then what the map's colours mean.
std::vector<LegendEntry> LegendEntries(const MapModel& map, const MapPictureContent& content) {
  std::vector<const TrajectoryLayer*> layers;
  for (const TrajectoryLayer& layer : content.layers) layers.push_back(&layer);
  std::stable_sort(layers.begin(), layers.end(),
                   [](const auto* a, const auto* b) { return a->kind > b->kind; });
  std::vector<LegendEntry> entries;
  for (const TrajectoryLayer* layer : layers) {
    const LayerStyle style = StyleOf(layer->kind);
    entries.push_back({layer->label, style.color, LegendMark::kLine, style.thickness});
  }
  if (content.shows_loops) {
    entries.push_back({fmt::format("loop closures ({})", content.loops.size()), kLoopColor,
                       LegendMark::kLink, 2});
  }
  if (map.walls()) {
    entries.push_back({"walls", kOccupiedCellColor, LegendMark::kLine, 2});
  } else {
    entries.push_back({"occupied", kOccupiedCellColor, LegendMark::kSwatch});
    entries.push_back({"free", kFreeCellColor, LegendMark::kSwatch});
    entries.push_back({"unexplored", kUnknownCellColor, LegendMark::kSwatch});
  }
  return entries;
}

}  // namespace

TrajectoryLayer MakeLayer(LayerKind kind, std::string label,
                          std::span<const StampedPose> trajectory) {
  TrajectoryLayer layer{kind, std::move(label), {}};
  layer.poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) layer.poses.push_back(p.pose);
  return layer;
}

Image DrawMapPicture(const MapModel& map, const MapPictureContent& content) {
  const WorldCanvas canvas = DrawMapArea(map, content);
  const Image& area = canvas.image();
  const int width = std::max(area.width() + 2 * kPad, kMinPictureWidth);
  const int inner = width - 2 * kPad;
  const int line = kLineAdvance * kTextScale;

  const std::vector<std::string> title = WrapText(content.title, inner, kTextScale);
  const int title_height = kPad + static_cast<int>(title.size()) * line;

  const ScaleBar bar =
      MakeScaleBar(canvas.metres_per_pixel(), std::max(area.width() / 4, inner / 8));
  const Eigen::Vector2i bar_size = ScaleBarSize(bar, kTextScale);
  const std::vector<LegendEntry> entries = LegendEntries(map, content);
  const int legend_width = inner - bar_size.x() - 2 * kPad;
  const int legend_height = LegendHeight(entries, legend_width, kTextScale);
  const int footer_height = 2 * kPad + std::max(legend_height, bar_size.y());

  // The map area's outline is a pixel wide on every side.
  const int area_top = title_height + 1;
  Image picture(width, area_top + area.height() + 1 + footer_height, kWhite);
  for (std::size_t i = 0; i < title.size(); ++i) {
    DrawText(picture, kPad, kPad + static_cast<int>(i) * line, title[i], kInkColor, kTextScale);
  }
  const int area_left = (width - area.width()) / 2;
  picture.FillRect(area_left - 1, area_top - 1, area.width() + 2, area.height() + 2, kFrameColor);
  picture.Paste(area, area_left, area_top);
  const int footer_top = area_top + area.height() + 1 + kPad;
  DrawLegend(picture, kPad, footer_top, legend_width, entries, kInkColor, kTextScale);
  DrawScaleBar(picture, width - kPad - bar_size.x(), footer_top, bar, kInkColor, kTextScale);
  return picture;
}

void WriteMapPicture(const MapModel& map, const MapPictureContent& content,
                     const std::filesystem::path& path) {
  WritePng(DrawMapPicture(map, content), path);
}

}  // namespace evoslam
