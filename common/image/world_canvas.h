#ifndef EVOSLAM_COMMON_IMAGE_WORLD_CANVAS_H_
#define EVOSLAM_COMMON_IMAGE_WORLD_CANVAS_H_

#include <Eigen/Core>
#include <span>

#include "common/image/image.h"
#include "common/transform/pose2.h"

namespace evoslam {

// An Image that covers a rectangle of the world, for drawing maps and trajectories in metres.
// World y points up, image rows run down. The canvas spans [min - margin, max + margin] on both
// axes, rounded up to whole pixels; the world point `min - margin` is the bottom-left corner of
// the bottom-left pixel. Thicknesses and radii are in pixels, so lines stay visible at any scale.
class WorldCanvas {
 public:
  static constexpr long long kMaxPixels = 1LL << 26;

  // Throws evoslam::Error for non-finite bounds, min > max, negative margin, non-positive
  // metres_per_pixel, or a canvas of more than kMaxPixels.
  WorldCanvas(const Eigen::Vector2d& min, const Eigen::Vector2d& max, double metres_per_pixel,
              double margin, Rgb background = {255, 255, 255});

  const Image& image() const { return image_; }
  Image& image() { return image_; }
  double metres_per_pixel() const { return metres_per_pixel_; }

  // Continuous pixel coordinates of a world point (pixel centres at integers), and back.
  Eigen::Vector2d ToPixel(const Eigen::Vector2d& world) const;
  Eigen::Vector2d ToWorld(const Eigen::Vector2d& pixel) const;

  void DrawSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color,
                   int thickness = 1);
  // Joins consecutive points; a single point is drawn as one brush stamp.
  void DrawPolyline(std::span<const Eigen::Vector2d> points, Rgb color, int thickness = 1);
  void DrawPoint(const Eigen::Vector2d& point, double radius_px, Rgb color);
  // A disc at the pose's position and a tick of length 2 * radius_px along its heading.
  void DrawPose(const Pose2& pose, Rgb color, double radius_px = 3.0, int thickness = 1);

 private:
  Eigen::Vector2d bottom_left_;  // world position of the image's bottom-left corner
  double metres_per_pixel_;
  Image image_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_WORLD_CANVAS_H_
