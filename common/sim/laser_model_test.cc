#include "common/sim/laser_model.h"

#include <gtest/gtest.h>

#include <numbers>

#include "common/util/error.h"

namespace evoslam {
namespace {

using std::numbers::pi;

TEST(LaserModelTest, DefaultIsSickPls100) {
  const LaserModel laser;
  EXPECT_EQ(laser.beams, 361);
  EXPECT_DOUBLE_EQ(laser.angle_min(), -pi / 2);
  EXPECT_DOUBLE_EQ(laser.angle_increment(), pi / 360);
  EXPECT_NEAR(laser.angle(180), 0.0, 1e-15);
  EXPECT_NEAR(laser.angle(360), pi / 2, 1e-15);  // both ends of the half-circle
  EXPECT_EQ(laser.max_range, 8.0);
  EXPECT_NO_THROW(CheckLaserModel(laser));
}

TEST(LaserModelTest, OtherLayouts) {
  const LaserModel wide{.beams = 241, .field_of_view_deg = 240};
  EXPECT_DOUBLE_EQ(wide.angle_min(), -2 * pi / 3);
  EXPECT_NEAR(wide.angle_increment(), pi / 180, 1e-15);
  const LaserModel single{.beams = 1};
  EXPECT_EQ(single.angle_increment(), 0.0);
  EXPECT_DOUBLE_EQ(single.angle(0), -pi / 2);
}

TEST(LaserModelTest, RejectsBadModels) {
  EXPECT_THROW(CheckLaserModel({.beams = 0}), Error);
  EXPECT_THROW(CheckLaserModel({.field_of_view_deg = 0}), Error);
  EXPECT_THROW(CheckLaserModel({.field_of_view_deg = 400}), Error);
  EXPECT_THROW(CheckLaserModel({.max_range = 0}), Error);
  EXPECT_THROW(CheckLaserModel({.max_range = 5, .min_range = 6}), Error);
  EXPECT_THROW(CheckLaserModel({.min_range = -1}), Error);
}

}  // namespace
}  // namespace evoslam
