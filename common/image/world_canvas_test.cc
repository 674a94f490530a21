#include "common/image/world_canvas.h"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>
#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr Rgb kBlue{0, 0, 255};

TEST(WorldCanvasTest, SizeCoversBoundsAndMargin) {
  const WorldCanvas canvas({-1.0, 2.0}, {3.0, 4.0}, 0.1, 0.5);
  EXPECT_EQ(canvas.image().width(), 50);   // (4 + 1) / 0.1
  EXPECT_EQ(canvas.image().height(), 30);  // (2 + 1) / 0.1
  const WorldCanvas point({1.0, 1.0}, {1.0, 1.0}, 0.1, 0.0);
  EXPECT_EQ(point.image().width(), 1);
  EXPECT_EQ(point.image().height(), 1);
}

TEST(WorldCanvasTest, YUpMapsToRowsDown) {
  const WorldCanvas canvas({0.0, 0.0}, {10.0, 5.0}, 1.0, 0.0);
  // Bottom-left world corner cell is the last row, first column.
  EXPECT_TRUE(canvas.ToPixel({0.5, 0.5}).isApprox(Eigen::Vector2d(0.0, 4.0)));
  EXPECT_TRUE(canvas.ToPixel({9.5, 4.5}).isApprox(Eigen::Vector2d(9.0, 0.0)));
  const Eigen::Vector2d w(3.3, 1.7);
  EXPECT_TRUE(canvas.ToWorld(canvas.ToPixel(w)).isApprox(w));
}

TEST(WorldCanvasTest, DrawSegmentLandsOnWorldCells) {
  WorldCanvas canvas({0.0, 0.0}, {10.0, 5.0}, 1.0, 0.0);
  canvas.DrawSegment({0.5, 1.5}, {9.5, 1.5}, kBlue);
  for (int x = 0; x < 10; ++x) {
    for (int y = 0; y < 5; ++y) EXPECT_EQ(canvas.image().at(x, y) == kBlue, y == 3) << x << y;
  }
}

TEST(WorldCanvasTest, PolylineJoinsPoints) {
  WorldCanvas canvas({0.0, 0.0}, {4.0, 4.0}, 1.0, 0.0);
  const std::vector<Eigen::Vector2d> points{{0.5, 0.5}, {3.5, 0.5}, {3.5, 3.5}};
  canvas.DrawPolyline(points, kBlue);
  int blue = 0;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) blue += canvas.image().at(x, y) == kBlue;
  }
  EXPECT_EQ(blue, 7);
  EXPECT_EQ(canvas.image().at(0, 3), kBlue);
  EXPECT_EQ(canvas.image().at(3, 0), kBlue);
  EXPECT_EQ(canvas.image().at(0, 0), kWhite);

  WorldCanvas single({0.0, 0.0}, {4.0, 4.0}, 1.0, 0.0);
  const std::vector<Eigen::Vector2d> one{{1.5, 2.5}};
  single.DrawPolyline(one, kBlue);
  EXPECT_EQ(single.image().at(1, 1), kBlue);
}

TEST(WorldCanvasTest, PoseTickPointsAlongHeading) {
  WorldCanvas canvas({0.0, 0.0}, {20.0, 20.0}, 1.0, 0.0);
  canvas.DrawPose(Pose2(10.5, 10.5, std::numbers::pi / 2), kBlue, 2.0);
  // Centre pixel (10, 9); heading up in the world is up in the image: tick reaches row 5.
  EXPECT_EQ(canvas.image().at(10, 9), kBlue);
  EXPECT_EQ(canvas.image().at(10, 5), kBlue);
  EXPECT_EQ(canvas.image().at(10, 13), kWhite);  // nothing behind beyond the disc
  EXPECT_EQ(canvas.image().at(10, 11), kBlue);   // disc
}

TEST(WorldCanvasTest, RejectsBadParameters) {
  EXPECT_THROW(WorldCanvas({0, 0}, {1, 1}, 0.0, 0.0), Error);
  EXPECT_THROW(WorldCanvas({0, 0}, {1, 1}, -1.0, 0.0), Error);
  EXPECT_THROW(WorldCanvas({2, 0}, {1, 1}, 0.1, 0.0), Error);
  EXPECT_THROW(WorldCanvas({0, 0}, {1, 1}, 0.1, -0.1), Error);
  EXPECT_THROW(WorldCanvas({0, 0}, {1e9, 1e9}, 0.01, 0.0), Error);
  EXPECT_THROW(WorldCanvas({0, 0}, {std::numeric_limits<double>::infinity(), 1}, 0.1, 0.0), Error);
}

}  // namespace
}  // namespace evoslam
