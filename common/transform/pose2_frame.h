#ifndef EVOSLAM_COMMON_TRANSFORM_POSE2_FRAME_H_
#define EVOSLAM_COMMON_TRANSFORM_POSE2_FRAME_H_

#include <Eigen/Core>
#include <cmath>

#include "common/transform/pose2.h"

namespace evoslam {

// A pose with its heading's cosine and sine worked out once, for the loops that compose or apply
// the same pose many times (a search scores thousands of poses a second, each on hundreds of
// points). Its products are Pose2's to the bit: Pose2's own products are computed through it.
class Pose2Frame {
 public:
  Pose2Frame() = default;  // the identity
  explicit Pose2Frame(const Pose2& pose)
      : pose_(pose), cos_(std::cos(pose.theta())), sin_(std::sin(pose.theta())) {}

  const Pose2& pose() const { return pose_; }
  double cos() const { return cos_; }
  double sin() const { return sin_; }

  // pose() * other.
  Pose2 operator*(const Pose2& other) const {
    return {pose_.x() + cos_ * other.x() - sin_ * other.y(),
            pose_.y() + sin_ * other.x() + cos_ * other.y(), pose_.theta() + other.theta()};
  }
  // pose() * point.
  Eigen::Vector2d operator*(const Eigen::Vector2d& point) const {
    return {pose_.x() + cos_ * point.x() - sin_ * point.y(),
            pose_.y() + sin_ * point.x() + cos_ * point.y()};
  }

 private:
  Pose2 pose_;
  double cos_ = 1.0, sin_ = 0.0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_TRANSFORM_POSE2_FRAME_H_
