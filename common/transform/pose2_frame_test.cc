#include "common/transform/pose2_frame.h"

#include <gtest/gtest.h>

#include <cmath>

namespace evoslam {
namespace {

TEST(Pose2FrameTest, HoldsTheHeadingsCosineAndSine) {
  const Pose2 pose(1.0, -2.0, 2.5);
  const Pose2Frame frame(pose);
  EXPECT_EQ(frame.pose(), pose);
  EXPECT_EQ(frame.cos(), std::cos(pose.theta()));
  EXPECT_EQ(frame.sin(), std::sin(pose.theta()));
  const Pose2Frame identity;
  EXPECT_EQ(identity.pose(), Pose2());
  EXPECT_EQ(identity * Eigen::Vector2d(0.3, -0.7), Eigen::Vector2d(0.3, -0.7));
}

TEST(Pose2FrameTest, ProductsAreRigidMotionsAndPose2sToTheBit) {
  // Searches compose poses through frames and must give the trajectories Pose2 gives.
  const Pose2 a(3.0, -4.0, 2.9), b(-0.5, 0.7, 1.1);
  const Pose2Frame frame(a);
  const Pose2 ab = frame * b;
  EXPECT_EQ(ab, a * b);
  EXPECT_NEAR(ab.theta(), 4.0 - 2 * 3.141592653589793, 1e-12);  // wrapped
  const Eigen::Vector2d p(0.25, 1.5);
  const Eigen::Vector2d moved = frame * p;
  EXPECT_EQ(moved, a * p);
  EXPECT_NEAR((moved - a.translation()).norm(), p.norm(), 1e-12);  // a rotation keeps lengths
  EXPECT_NEAR(moved.x(), 3.0 + std::cos(2.9) * 0.25 - std::sin(2.9) * 1.5, 1e-12);
}

}  // namespace
}  // namespace evoslam
