#include "common/io/carmen_format.h"
#include "common/transform/angle_units.h"

#include <gtest/gtest.h>

#include <numbers>

namespace evoslam {
namespace {

TEST(CarmenFormatTest, FlaserIncrementFollowsTheBeamCount) {
  EXPECT_NEAR(FlaserAngleIncrement(180), 1.0 * kDegree, 1e-15);  // -90 .. +89 deg
  EXPECT_NEAR(FlaserAngleIncrement(181), 1.0 * kDegree, 1e-15);  // -90 .. +90 deg
  EXPECT_NEAR(FlaserAngleIncrement(361), 0.5 * kDegree, 1e-15);  // -90 .. +90 deg
  EXPECT_NEAR(FlaserAngleIncrement(360), 0.5 * kDegree, 1e-15);
  EXPECT_EQ(FlaserAngleIncrement(1), 0.0);
  EXPECT_EQ(FlaserAngleIncrement(0), 0.0);
}

TEST(CarmenFormatTest, OddCountsEndAtPlusNinetyDegrees) {
  for (const std::size_t n : {181u, 361u, 721u}) {
    const double last = kFlaserAngleMin + static_cast<double>(n - 1) * FlaserAngleIncrement(n);
    EXPECT_NEAR(last, std::numbers::pi / 2.0, 1e-12) << n;
  }
  EXPECT_NEAR(kFlaserAngleMin, -90.0 * kDegree, 1e-15);
}

TEST(CarmenFormatTest, DefaultRangeMaxExcludesTheNoReturnMarkersOfRealLogs) {
  // "No return" readings of ACES, Intel and MIT CSAIL must not count as returns.
  for (const double marker : {50.0, 81.83, 81.91}) EXPECT_GE(marker, kCarmenDefaultRangeMax);
  // Their largest real readings must.
  for (const double reading : {49.91, 26.37, 42.40}) EXPECT_LT(reading, kCarmenDefaultRangeMax);
}

TEST(CarmenFormatTest, RangeMaxComesFromTheLastMatchingParam) {
  using Params = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(CarmenRangeMax({}, false), kCarmenDefaultRangeMax);
  EXPECT_EQ(CarmenRangeMax({}, true), kCarmenDefaultRangeMax);
  const Params front = {{"robot_front_laser_max", "30"}, {"laser_front_laser_max_range", "40.5"}};
  EXPECT_EQ(CarmenRangeMax(front, false), 40.5);
  EXPECT_EQ(CarmenRangeMax(front, true), 40.5);  // the rear laser falls back to the front's
  const Params both = {{"laser_front_laser_max_range", "40"}, {"robot_rear_laser_max", "8"}};
  EXPECT_EQ(CarmenRangeMax(both, false), 40.0);
  EXPECT_EQ(CarmenRangeMax(both, true), 8.0);
  const Params invalid = {{"laser_front_laser_max_range", "far"}, {"robot_front_laser_max", "-3"}};
  EXPECT_EQ(CarmenRangeMax(invalid, false), kCarmenDefaultRangeMax);
}

TEST(CarmenFormatTest, RangeMaxParamMustBePositive) {
  EXPECT_EQ(ParseRangeMaxParam("81.9"), 81.9);
  EXPECT_FALSE(ParseRangeMaxParam("0"));
  EXPECT_FALSE(ParseRangeMaxParam("-1"));
  EXPECT_FALSE(ParseRangeMaxParam("inf"));
  EXPECT_FALSE(ParseRangeMaxParam("8m"));
  EXPECT_TRUE(IsRangeMaxParam("robot_front_laser_max", false));
  EXPECT_FALSE(IsRangeMaxParam("robot_front_laser_max", true));
  EXPECT_TRUE(IsRangeMaxParam("laser_rear_laser_max_range", true));
}

}  // namespace
}  // namespace evoslam
