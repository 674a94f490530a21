#include "common/image/world_canvas.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/util/error.h"

namespace evoslam {
namespace {

// Number of pixels needed to cover `extent` metres; at least one.
double PixelsFor(double extent, double metres_per_pixel) {
  return std::max(1.0, std::ceil(extent / metres_per_pixel));
}

}  // namespace

WorldCanvas::WorldCanvas(const Eigen::Vector2d& min, const Eigen::Vector2d& max,
                         double metres_per_pixel, double margin, Rgb background)
    : bottom_left_((min.array() - margin).matrix()), metres_per_pixel_(metres_per_pixel) {
  if (!min.allFinite() || !max.allFinite() || !std::isfinite(margin) ||
      !std::isfinite(metres_per_pixel)) {
    throw Error("world canvas: bounds, margin and scale must be finite");
  }
  if (min.x() > max.x() || min.y() > max.y()) {
    std::ostringstream os;
    os << "world canvas: min (" << min.transpose() << ") exceeds max (" << max.transpose() << ")";
    throw Error(os.str());
  }
  if (margin < 0.0) throw Error("world canvas: margin must not be negative");
  if (metres_per_pixel <= 0.0) throw Error("world canvas: metres per pixel must be positive");
  const double width = PixelsFor(max.x() - min.x() + 2.0 * margin, metres_per_pixel);
  const double height = PixelsFor(max.y() - min.y() + 2.0 * margin, metres_per_pixel);
  if (width * height > static_cast<double>(kMaxPixels)) {
    std::ostringstream os;
    os << "world canvas of " << width << " x " << height << " pixels exceeds " << kMaxPixels
       << "; use more metres per pixel";
    throw Error(os.str());
  }
  image_ = Image(static_cast<int>(width), static_cast<int>(height), background);
}

Eigen::Vector2d WorldCanvas::ToPixel(const Eigen::Vector2d& world) const {
  return {(world.x() - bottom_left_.x()) / metres_per_pixel_ - 0.5,
          image_.height() - (world.y() - bottom_left_.y()) / metres_per_pixel_ - 0.5};
}

Eigen::Vector2d WorldCanvas::ToWorld(const Eigen::Vector2d& pixel) const {
  return {bottom_left_.x() + (pixel.x() + 0.5) * metres_per_pixel_,
          bottom_left_.y() + (image_.height() - pixel.y() - 0.5) * metres_per_pixel_};
}

void WorldCanvas::DrawSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color,
                              int thickness) {
  const Eigen::Vector2d pa = ToPixel(a);
  const Eigen::Vector2d pb = ToPixel(b);
  image_.DrawLine(pa.x(), pa.y(), pb.x(), pb.y(), color, thickness);
}

void WorldCanvas::DrawPolyline(std::span<const Eigen::Vector2d> points, Rgb color, int thickness) {
  if (points.size() == 1) DrawSegment(points[0], points[0], color, thickness);
  for (std::size_t i = 1; i < points.size(); ++i) {
    DrawSegment(points[i - 1], points[i], color, thickness);
  }
}

void WorldCanvas::DrawPoint(const Eigen::Vector2d& point, double radius_px, Rgb color) {
  const Eigen::Vector2d p = ToPixel(point);
  image_.DrawDisc(p.x(), p.y(), radius_px, color);
}

void WorldCanvas::DrawPose(const Pose2& pose, Rgb color, double radius_px, int thickness) {
  const Eigen::Vector2d p = ToPixel(pose.translation());
  image_.DrawDisc(p.x(), p.y(), radius_px, color);
  // Image rows run down, so the heading's y component flips.
  const double tick = 2.0 * radius_px;
  image_.DrawLine(p.x(), p.y(), p.x() + tick * std::cos(pose.theta()),
                  p.y() - tick * std::sin(pose.theta()), color, thickness);
}

}  // namespace evoslam
