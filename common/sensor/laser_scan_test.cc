#include "common/sensor/laser_scan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "common/sensor/dataset.h"
#include "common/transform/angle_units.h"

namespace evoslam {
namespace {

LaserScan Scan(std::vector<float> ranges) {
  LaserScan s;
  s.angle_min = -90 * kDegree;
  s.angle_increment = 1 * kDegree;
  s.range_max = 8.0;
  s.ranges = std::move(ranges);
  return s;
}

TEST(LaserScanTest, BeamAnglesAndFieldOfView) {
  const LaserScan s = Scan(std::vector<float>(181, 1.0f));
  EXPECT_DOUBLE_EQ(s.angle(0), -90 * kDegree);
  EXPECT_NEAR(s.angle(90), 0.0, 1e-15);
  EXPECT_NEAR(s.angle(180), 90 * kDegree, 1e-12);
  EXPECT_NEAR(s.field_of_view(), 180 * kDegree, 1e-12);
  EXPECT_EQ(Scan({}).field_of_view(), 0.0);
}

TEST(LaserScanTest, OnlyReadingsInsideTheSensorRangeAreReturns) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const LaserScan s = Scan({2.5f, 0.0f, 8.0f, 9.0f, nan, inf, 7.99f});
  EXPECT_TRUE(s.is_return(0));
  EXPECT_FALSE(s.is_return(1));  // zero: no echo
  EXPECT_FALSE(s.is_return(2));  // at range_max: the no-return marker
  EXPECT_FALSE(s.is_return(3));
  EXPECT_FALSE(s.is_return(4));
  EXPECT_FALSE(s.is_return(5));
  EXPECT_TRUE(s.is_return(6));
}

TEST(DatasetTest, GroundTruthOnlyWhenEveryScanHasIt) {
  Dataset d;
  d.scans.assign(3, Scan({1.0f}));
  EXPECT_FALSE(d.has_ground_truth());
  for (auto& s : d.scans) s.true_pose = Pose2(1, 2, 0.3);
  EXPECT_TRUE(d.has_ground_truth());
  d.scans[1].true_pose.reset();
  EXPECT_FALSE(d.has_ground_truth());
}

}  // namespace
}  // namespace evoslam
