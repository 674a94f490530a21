#include "common/transform/pose2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace evoslam {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WrapAngleTest, LeavesAnAngleInsideTheIntervalAsItIs) {
  for (double a = -kPi; a <= kPi; a += 0.001) {
    const double inside = a > -kPi ? a : kPi;
    EXPECT_EQ(WrapAngle(a), inside) << a;
  }
}

TEST(WrapAngleTest, MapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(WrapAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(WrapAngle(-kPi), kPi);
  EXPECT_NEAR(WrapAngle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(WrapAngle(2 * kPi + 0.25), 0.25, 1e-12);
  EXPECT_NEAR(WrapAngle(-2 * kPi - 0.25), -0.25, 1e-12);
  EXPECT_NEAR(WrapAngle(1.5 * kPi), -0.5 * kPi, 1e-12);
}

TEST(Pose2Test, ComposeMatchesHomogeneousMatrices) {
  const Pose2 a(1.0, 2.0, 0.3);
  const Pose2 b(-0.5, 0.7, 1.1);
  const auto h = [](const Pose2& p) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
    m.topLeftCorner<2, 2>() = p.rotation();
    m.topRightCorner<2, 1>() = p.translation();
    return m;
  };
  const Eigen::Matrix3d expected = h(a) * h(b);
  const Pose2 ab = a * b;
  EXPECT_TRUE(h(ab).isApprox(expected, 1e-12));
  EXPECT_NEAR(ab.theta(), 1.4, 1e-12);
}

TEST(Pose2Test, InverseUndoesPose) {
  const Pose2 a(3.0, -4.0, 2.5);
  const Pose2 id = a * a.inverse();
  EXPECT_NEAR(id.x(), 0.0, 1e-12);
  EXPECT_NEAR(id.y(), 0.0, 1e-12);
  EXPECT_NEAR(id.theta(), 0.0, 1e-12);
  const Eigen::Vector2d p(0.4, 9.0);
  EXPECT_TRUE((a.inverse() * (a * p)).isApprox(p, 1e-12));
}

TEST(Pose2Test, TransformsPointsRobotToWorld) {
  const Pose2 robot(1.0, 1.0, kPi / 2);
  const Eigen::Vector2d ahead = robot * Eigen::Vector2d(2.0, 0.0);
  EXPECT_NEAR(ahead.x(), 1.0, 1e-12);
  EXPECT_NEAR(ahead.y(), 3.0, 1e-12);
}

TEST(Pose2Test, HeadingIsWrappedOnConstruction) {
  EXPECT_NEAR(Pose2(0, 0, 2 * kPi + 0.1).theta(), 0.1, 1e-12);
  EXPECT_NEAR((Pose2(0, 0, 3.0) * Pose2(0, 0, 3.0)).theta(), 6.0 - 2 * kPi, 1e-12);
}

TEST(Pose2Test, InterpolateTakesShortestArc) {
  const Pose2 a(0, 0, kPi - 0.1);
  const Pose2 b(2, 4, -kPi + 0.1);
  const Pose2 mid = Interpolate(a, b, 0.5);
  EXPECT_NEAR(mid.x(), 1.0, 1e-12);
  EXPECT_NEAR(mid.y(), 2.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.theta()), kPi, 1e-12);
}

}  // namespace
}  // namespace evoslam
