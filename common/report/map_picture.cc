#include "common/report/map_picture.h"

#include <algorithm>

#include "common/grid/grid_image.h"
#include "common/image/world_canvas.h"

namespace evoslam {
namespace {

Bounds PictureBounds(const MapModel& map, std::span<const TrajectoryLayer> layers) {
  Bounds b;
  bool any = false;
  const auto add = [&](const Eigen::Vector2d& p) {
    b.min = any ? b.min.cwiseMin(p) : p;
    b.max = any ? b.max.cwiseMax(p) : p;
    any = true;
  };
  if (const LineMap* walls = map.walls(); walls && !walls->empty()) {
    add(walls->bounds().min);
    add(walls->bounds().max);
  } else if (const OccupancyGrid* grid = map.grid()) {
    add(grid->min_corner());
    add(grid->max_corner());
  }
  for (const auto& layer : layers) {
    for (const Pose2& p : layer.poses) add(p.translation());
  }
  if (!any) b.max = {1.0, 1.0};
  return b;
}

}  // namespace

TrajectoryLayer MakeLayer(std::string name, std::span<const StampedPose> trajectory, Rgb color) {
  TrajectoryLayer layer{std::move(name), {}, color};
  layer.poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) layer.poses.push_back(p.pose);
  return layer;
}

WorldCanvas DrawMapPicture(const MapModel& map, std::span<const TrajectoryLayer> layers,
                           int max_pixels) {
  const Bounds bounds = PictureBounds(map, layers);
  const Eigen::Vector2d size = bounds.max - bounds.min;
  const double extent = std::max({size.x(), size.y(), 1.0});
  const double margin = 0.03 * extent;
  const double metres_per_pixel = (extent + 2 * margin) / max_pixels;
  WorldCanvas canvas(bounds.min, bounds.max, metres_per_pixel, margin);

  if (const LineMap* walls = map.walls()) {
    for (const Segment& s : walls->segments()) canvas.DrawSegment(s.a, s.b, {0, 0, 0}, 2);
  } else if (const OccupancyGrid* grid = map.grid()) {
    DrawGrid(*grid, canvas);
  }
  for (const auto& layer : layers) {
    std::vector<Eigen::Vector2d> points;
    points.reserve(layer.poses.size());
    for (const Pose2& p : layer.poses) points.push_back(p.translation());
    canvas.DrawPolyline(points, layer.color, 2);
    if (!layer.poses.empty()) canvas.DrawPose(layer.poses.front(), layer.color, 5.0, 2);
  }
  return canvas;
}

void WriteMapPicture(const MapModel& map, std::span<const TrajectoryLayer> layers,
                     const std::filesystem::path& path, int max_pixels) {
  WritePng(DrawMapPicture(map, layers, max_pixels).image(), path);
}

}  // namespace evoslam
