#ifndef EVOSLAM_COMMON_TRANSFORM_POSE2_H_
#define EVOSLAM_COMMON_TRANSFORM_POSE2_H_

#include <Eigen/Core>
#include <iosfwd>
#include <numbers>

namespace evoslam {

// Wraps an angle in radians to (-pi, pi]. Inline with a test for an angle already there (the
// usual case, and remainder's answer to the bit), as every pose composed is wrapped.
double WrapAngleOutside(double angle);
inline double WrapAngle(double angle) {
  return angle > -std::numbers::pi && angle <= std::numbers::pi ? angle : WrapAngleOutside(angle);
}

// A rigid motion in the plane, SE(2): rotation by theta, then translation by (x, y).
// As a robot pose it maps points from the robot frame into the world frame.
class Pose2 {
 public:
  Pose2() = default;
  Pose2(double x, double y, double theta) : x_(x), y_(y), theta_(WrapAngle(theta)) {}
  Pose2(const Eigen::Vector2d& translation, double theta)
      : Pose2(translation.x(), translation.y(), theta) {}

  double x() const { return x_; }
  double y() const { return y_; }
  double theta() const { return theta_; }
  Eigen::Vector2d translation() const { return {x_, y_}; }
  Eigen::Matrix2d rotation() const;

  // this * other: first other, then this (other expressed in this frame).
  Pose2 operator*(const Pose2& other) const;
  Eigen::Vector2d operator*(const Eigen::Vector2d& point) const;
  Pose2 inverse() const;

  bool operator==(const Pose2&) const = default;

 private:
  double x_ = 0.0;
  double y_ = 0.0;
  double theta_ = 0.0;
};

// Linear interpolation of translation and shortest-arc interpolation of heading; s in [0, 1].
Pose2 Interpolate(const Pose2& a, const Pose2& b, double s);

std::ostream& operator<<(std::ostream& os, const Pose2& pose);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_TRANSFORM_POSE2_H_
