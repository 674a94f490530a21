#include "common/transform/pose2.h"

#include <cmath>
#include <numbers>
#include <ostream>

#include "common/transform/pose2_frame.h"

namespace evoslam {

double WrapAngleOutside(double angle) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double wrapped = std::remainder(angle, kTwoPi);  // in [-pi, pi]
  if (wrapped <= -std::numbers::pi) wrapped += kTwoPi;
  return wrapped;
}

Eigen::Matrix2d Pose2::rotation() const {
  const double c = std::cos(theta_);
  const double s = std::sin(theta_);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Pose2 Pose2::operator*(const Pose2& other) const { return Pose2Frame(*this) * other; }

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& point) const {
  return Pose2Frame(*this) * point;
}

Pose2 Pose2::inverse() const {
  const double c = std::cos(theta_);
  const double s = std::sin(theta_);
  return {-c * x_ - s * y_, s * x_ - c * y_, -theta_};
}

Pose2 Interpolate(const Pose2& a, const Pose2& b, double s) {
  const double dtheta = WrapAngle(b.theta() - a.theta());
  return {a.x() + s * (b.x() - a.x()), a.y() + s * (b.y() - a.y()), a.theta() + s * dtheta};
}

std::ostream& operator<<(std::ostream& os, const Pose2& pose) {
  return os << "(" << pose.x() << ", " << pose.y() << ", " << pose.theta() << ")";
}

}  // namespace evoslam
