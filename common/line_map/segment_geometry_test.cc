#include "common/line_map/segment_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace evoslam {
namespace {

TEST(SegmentGeometryTest, PointSegmentDistance) {
  const Segment s{{0, 0}, {4, 0}};
  EXPECT_DOUBLE_EQ(PointSegmentDistance({2, 3}, s), 3.0);   // above the middle
  EXPECT_DOUBLE_EQ(PointSegmentDistance({-3, 4}, s), 5.0);  // beyond end a
  EXPECT_DOUBLE_EQ(PointSegmentDistance({7, -4}, s), 5.0);  // beyond end b
  EXPECT_DOUBLE_EQ(PointSegmentDistance({1, 0}, s), 0.0);   // on the segment
  EXPECT_DOUBLE_EQ(PointSegmentDistance({1, 1}, {{2, 2}, {2, 2}}), std::sqrt(2.0));
  // Diagonal segment x + y = 2: the origin is sqrt(2) from its middle.
  EXPECT_NEAR(PointSegmentDistance({0, 0}, {{2, 0}, {0, 2}}), std::sqrt(2.0), 1e-15);
}

TEST(SegmentGeometryTest, SegmentSegmentDistance) {
  const Segment s{{0, 0}, {4, 0}};
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{2, -1}, {2, 1}}), 0.0);  // crossing
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{2, 0}, {2, 1}}), 0.0);   // touching (T)
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{1, 1}, {3, 1}}), 1.0);   // parallel
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{6, 0}, {9, 0}}), 2.0);   // collinear, apart
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{3, 0}, {9, 0}}), 0.0);   // collinear, overlap
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{5, 1}, {5, 5}}), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance(s, {{2, 3}, {2, 3}}), 3.0);  // zero length
  // Crossing at a shallow angle far from every endpoint.
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance({{0, -1}, {10, 1}}, {{0, 1}, {10, -1}}), 0.0);
}

}  // namespace
}  // namespace evoslam
