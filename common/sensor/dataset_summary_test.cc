#include "common/sensor/dataset_summary.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

namespace evoslam {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;

LaserScan Scan(double timestamp, std::size_t beams, double increment, const Pose2& odometry) {
  LaserScan scan;
  scan.timestamp = timestamp;
  scan.angle_min = -kPi / 2;
  scan.angle_increment = increment;
  scan.range_max = 30.0;
  scan.ranges.assign(beams, 1.0F);
  scan.odometry = odometry;
  scan.pose = Pose2(100, 100, 0);  // must not be used for the odometry path
  return scan;
}

// Scan odometry goes 3 m east, 4 m north, then back to the start: a 3-4-5 triangle.
Dataset Triangle() {
  Dataset d;
  d.scans = {Scan(10.0, 181, kPi / 180, Pose2(0, 0, 0)), Scan(11.0, 181, kPi / 180, Pose2(3, 0, 1)),
             Scan(12.0, 361, kPi / 360, Pose2(3, 4, 2)),
             Scan(13.0, 181, kPi / 180, Pose2(0, 0, 3))};
  d.scans[1].range_max = 80.0;
  return d;
}

TEST(DatasetSummaryTest, SummarisesScansFromTheirOdometry) {
  const DatasetSummary s = Summarize(Triangle());
  EXPECT_EQ(s.scans, 4u);
  EXPECT_EQ(s.rear_scans, 0u);
  EXPECT_EQ(s.odometry_readings, 0u);
  EXPECT_EQ(s.min_beams, 181u);
  EXPECT_EQ(s.max_beams, 361u);
  EXPECT_NEAR(s.field_of_view_deg, 180.0, 1e-9);
  EXPECT_NEAR(s.angle_increment_deg, 1.0, 1e-12);
  EXPECT_EQ(s.max_range, 80.0);
  EXPECT_EQ(s.start_time, 10.0);
  EXPECT_EQ(s.end_time, 13.0);
  EXPECT_EQ(s.duration, 3.0);
  EXPECT_NEAR(s.odometry_path_length, 3.0 + 4.0 + 5.0, 1e-12);
  EXPECT_FALSE(s.has_ground_truth);
}

TEST(DatasetSummaryTest, PrefersOdometryReadingsAndSpansAllMessages) {
  Dataset d = Triangle();
  for (const auto& [t, x] : {std::pair{9.5, 0.0}, {10.5, 1.0}, {11.5, 1.0}, {14.0, -1.5}}) {
    OdometryReading odom;
    odom.timestamp = t;
    odom.pose = Pose2(x, 0, 0);
    d.odometry.push_back(odom);
  }
  d.rear_scans = {Scan(14.5, 10, 0.1, Pose2())};
  for (LaserScan& scan : d.scans) scan.true_pose = Pose2();
  const DatasetSummary s = Summarize(d);
  EXPECT_EQ(s.odometry_readings, 4u);
  EXPECT_EQ(s.rear_scans, 1u);
  EXPECT_NEAR(s.odometry_path_length, 1.0 + 0.0 + 2.5, 1e-12);
  EXPECT_EQ(s.start_time, 9.5);
  EXPECT_EQ(s.end_time, 14.5);
  EXPECT_EQ(s.duration, 5.0);
  EXPECT_TRUE(s.has_ground_truth);
}

TEST(DatasetSummaryTest, CountsTheRunsOfRepeatedOdometryAndTheStepsThatEndThem) {
  Dataset d;
  for (const Pose2& odometry :
       {Pose2(0, 0, 0), Pose2(0, 0, 0), Pose2(0, 0, 0), Pose2(0.5, 0, 0.3), Pose2(0.6, 0, 0.3),
        Pose2(0.6, 0, 0.3), Pose2(0.62, 0, 1.0), Pose2(0.62, 0, 1.4), Pose2(0.62, 0, 1.8),
        Pose2(0.9, 0, 1.8), Pose2(0.9, 0, 1.8)}) {
    d.scans.push_back(
        Scan(10.0 + 0.2 * static_cast<double>(d.scans.size()), 181, kPi / 180, odometry));
  }
  const DatasetSummary s = Summarize(d);
  // Scans 1 and 2, then 5. Turning on the spot at scans 7 and 8 repeats no whole reading, and the
  // repeat at the end has no step after it.
  EXPECT_EQ(s.odometry_repeats, 2u);
  EXPECT_EQ(s.longest_odometry_repeat, 2u);
  EXPECT_NEAR(s.largest_catch_up_m, 0.5, 1e-12);
  EXPECT_NEAR(s.largest_catch_up_deg, 0.7 * 180.0 / kPi, 1e-9);
  EXPECT_THAT(FormatSummary(s), HasSubstr("odometry repeats:  2 runs of scans, the longest 2; the "
                                          "steps that end them up to 0.50 m and 40.1 deg\n"));
  EXPECT_THAT(FormatSummary(Summarize(Triangle())), HasSubstr("odometry repeats:  none\n"));
}

TEST(DatasetSummaryTest, EmptyDatasetIsAllZero) {
  const DatasetSummary s = Summarize(Dataset{});
  EXPECT_EQ(s.scans, 0u);
  EXPECT_EQ(s.max_beams, 0u);
  EXPECT_EQ(s.duration, 0.0);
  EXPECT_EQ(s.odometry_path_length, 0.0);
  EXPECT_FALSE(s.has_ground_truth);
}

TEST(DatasetSummaryTest, FormatShowsTheFigures) {
  const std::string text = FormatSummary(Summarize(Triangle()));
  EXPECT_THAT(text, HasSubstr("4 (front)"));
  EXPECT_THAT(text, HasSubstr("181 to 361"));
  EXPECT_THAT(text, HasSubstr("180.00 deg"));
  EXPECT_THAT(text, HasSubstr("80.00 m"));
  EXPECT_THAT(text, HasSubstr("12.00 m"));
  EXPECT_THAT(text, HasSubstr("ground truth:      no"));
  EXPECT_EQ(text.back(), '\n');
}

}  // namespace
}  // namespace evoslam
