#include "common/io/carmen_reader.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>

#include "common/io/testing_files.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using io_testing::Bzip2Bytes;
using io_testing::GzipBytes;
using io_testing::WriteBytes;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Beam i of the test scans reads 1 + i/100 m, written with 2 decimals.
std::string RangeText(std::size_t i) { return fmt::format("{:.2f}", 1.0 + i / 100.0); }
float TestRange(std::size_t i) { return std::strtof(RangeText(i).c_str(), nullptr); }

std::string Ranges(std::size_t n) {
  std::string text;
  for (std::size_t i = 0; i < n; ++i) text += " " + RangeText(i);
  return text;
}

// A FLASER/RLASER line with n beams, pose (1, 2, 0.5), odometry (1.5, 2.5, 0.25).
std::string FlaserLine(std::size_t n, double timestamp, std::string_view name = "FLASER") {
  return fmt::format("{} {}{} 1 2 0.5 1.5 2.5 0.25 {:.6f} myhost {:.6f}", name, n, Ranges(n),
                     timestamp, timestamp + 0.5);
}

std::string OdomLine(double x, double timestamp) {
  return fmt::format("ODOM {} 0 0.1 0.3 0.02 0 {:.6f} nohost {:.6f}", x, timestamp, timestamp);
}

std::filesystem::path WriteLog(const TempDir& dir, const std::string& text,
                               std::string_view name = "log.clf") {
  const auto path = dir / name;
  WriteBytes(path, text);
  return path;
}

InputError ReadError(const std::filesystem::path& path) {
  try {
    ReadCarmen(path);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError reading " << path;
  return InputError("", 0, "");
}

TEST(CarmenReaderTest, ReadsMessagesInLogOrder) {
  TempDir dir;
  const std::string log =
      "# a comment\n"
      "\n"
      "PARAM robot_frontlaser_offset 0.0 nohost 0\n"
      "PARAM robot_use_laser on\n" +
      OdomLine(0.0, 10.0) + "\n" + FlaserLine(180, 10.25) + "\n" +
      "SYNC tag\n"
      "NMEA-GGA 1 2 3 4 5\n"
      "SOMETHINGNEW 1 2\n" +
      OdomLine(0.5, 10.5) + "\n" + FlaserLine(180, 10.75) + "\n";
  CarmenReadStats stats;
  const Dataset d = ReadCarmen(WriteLog(dir, log), {}, &stats);
  EXPECT_EQ(stats.lines, 11u);
  EXPECT_EQ(stats.skipped, 0u);
  EXPECT_EQ(d.source, (dir / "log.clf").string());
  ASSERT_EQ(d.params.size(), 2u);
  EXPECT_EQ(d.params[0],
            std::make_pair(std::string("robot_frontlaser_offset"), std::string("0.0")));
  EXPECT_EQ(d.params[1], std::make_pair(std::string("robot_use_laser"), std::string("on")));

  ASSERT_EQ(d.odometry.size(), 2u);
  EXPECT_EQ(d.odometry[0].pose, Pose2(0.0, 0.0, 0.1));
  EXPECT_EQ(d.odometry[1].pose.x(), 0.5);
  EXPECT_EQ(d.odometry[0].tv, 0.3);
  EXPECT_EQ(d.odometry[0].rv, 0.02);
  EXPECT_EQ(d.odometry[1].timestamp, 10.5);

  ASSERT_EQ(d.scans.size(), 2u);
  EXPECT_TRUE(d.rear_scans.empty());
  const LaserScan& s = d.scans[0];
  EXPECT_EQ(s.message, LaserMessage::kFront);
  EXPECT_EQ(s.timestamp, 10.25);
  EXPECT_EQ(s.logger_timestamp, 10.75);
  EXPECT_EQ(s.hostname, "myhost");
  EXPECT_EQ(s.pose, Pose2(1.0, 2.0, 0.5));
  EXPECT_EQ(s.odometry, Pose2(1.5, 2.5, 0.25));
  EXPECT_FALSE(s.true_pose);
  ASSERT_EQ(s.size(), 180u);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(s.ranges[i], TestRange(i)) << i;
  EXPECT_EQ(s.range_min, 0.0);
  EXPECT_EQ(d.scans[1].timestamp, 10.75);
}

TEST(CarmenReaderTest, BeamGeometrySpansTheHalfCircle) {
  TempDir dir;
  const Dataset d = ReadCarmen(WriteLog(
      dir, FlaserLine(180, 1) + "\n" + FlaserLine(181, 2) + "\n" + FlaserLine(361, 3) + "\n"));
  ASSERT_EQ(d.scans.size(), 3u);
  // 180 beams: 1 deg apart from -90 to +89 deg.
  EXPECT_NEAR(d.scans[0].angle(0), -90 * kDegree, 1e-12);
  EXPECT_NEAR(d.scans[0].angle_increment, 1 * kDegree, 1e-12);
  EXPECT_NEAR(d.scans[0].angle(179), 89 * kDegree, 1e-12);
  // 181 and 361 beams include both ends.
  EXPECT_NEAR(d.scans[1].angle(0), -90 * kDegree, 1e-12);
  EXPECT_NEAR(d.scans[1].angle(180), 90 * kDegree, 1e-12);
  EXPECT_NEAR(d.scans[2].angle_increment, 0.5 * kDegree, 1e-12);
  EXPECT_NEAR(d.scans[2].angle(360), 90 * kDegree, 1e-12);
  EXPECT_NEAR(d.scans[2].angle(180), 0.0, 1e-12);
}

TEST(CarmenReaderTest, RearLaserGoesToRearScans) {
  TempDir dir;
  const Dataset d =
      ReadCarmen(WriteLog(dir, FlaserLine(180, 1) + "\n" + FlaserLine(181, 1.5, "RLASER") + "\n"));
  ASSERT_EQ(d.scans.size(), 1u);
  ASSERT_EQ(d.rear_scans.size(), 1u);
  EXPECT_EQ(d.rear_scans[0].message, LaserMessage::kRear);
  EXPECT_EQ(d.rear_scans[0].size(), 181u);
  EXPECT_EQ(d.rear_scans[0].timestamp, 1.5);
}

TEST(CarmenReaderTest, DefaultRangeMaxMakesNoReturnMarkersNonReturns) {
  TempDir dir;
  const Dataset d =
      ReadCarmen(WriteLog(dir, "FLASER 4 1.5 81.83 81.91 50.00 0 0 0 0 0 0 1.0 nohost 1.0\n"));
  ASSERT_EQ(d.scans.size(), 1u);
  const LaserScan& s = d.scans[0];
  EXPECT_TRUE(s.is_return(0));
  EXPECT_FALSE(s.is_return(1));  // Intel's marker
  EXPECT_FALSE(s.is_return(2));  // MIT CSAIL's
  EXPECT_FALSE(s.is_return(3));  // ACES's
}

TEST(CarmenReaderTest, RangeMaxParamAppliesWhereverItIs) {
  TempDir dir;
  const Dataset d =
      ReadCarmen(WriteLog(dir, FlaserLine(180, 1) + "\n" + FlaserLine(180, 2, "RLASER") +
                                   "\nPARAM laser_front_laser_max_range 20.5 nohost 0\n"
                                   "PARAM robot_rear_laser_max 8 0.0 nohost 0\n"));
  EXPECT_EQ(d.scans[0].range_max, 20.5);
  EXPECT_EQ(d.rear_scans[0].range_max, 8.0);
  ASSERT_EQ(d.params.size(), 2u);
  EXPECT_EQ(d.params[1].second, "8");
}

TEST(CarmenReaderTest, ReadsRobotLaserWithItsOwnGeometry) {
  TempDir dir;
  // 5 beams from -45 deg every 22.5 deg, 2 remissions.
  const std::string line = fmt::format(
      "ROBOTLASER1 0 {} {} {} 30.0 0.01 0 5 1.0 2.0 3.0 4.0 5.0 2 0.5 0.6 "
      "7 8 0.3 7.1 8.2 0.4 0.1 0.2 1 2 1000000 55.5 robot 56.5",
      -45 * kDegree, 90 * kDegree, 22.5 * kDegree);
  const Dataset d = ReadCarmen(WriteLog(dir, line + "\n"));
  ASSERT_EQ(d.scans.size(), 1u);
  const LaserScan& s = d.scans[0];
  EXPECT_EQ(s.message, LaserMessage::kRobotLaser);
  EXPECT_NEAR(s.angle_min, -45 * kDegree, 1e-12);
  EXPECT_NEAR(s.angle_increment, 22.5 * kDegree, 1e-12);
  EXPECT_EQ(s.range_max, 30.0);
  EXPECT_EQ(s.range_min, 0.0);
  EXPECT_THAT(s.ranges, ::testing::ElementsAre(1.0F, 2.0F, 3.0F, 4.0F, 5.0F));
  EXPECT_EQ(s.pose, Pose2(7.1, 8.2, 0.4));
  EXPECT_EQ(s.odometry, s.pose);
  EXPECT_EQ(s.timestamp, 55.5);
  EXPECT_EQ(s.hostname, "robot");
  EXPECT_EQ(s.logger_timestamp, 56.5);
}

TEST(CarmenReaderTest, TrueposMatchesScansByTimestampInEitherOrder) {
  TempDir dir;
  const std::string log = "TRUEPOS 5 6 0.7 0 0 0 1.000000 nohost 1\n" + FlaserLine(180, 1.0) +
                          "\n" + FlaserLine(180, 2.0) + "\n" + FlaserLine(180, 3.0) + "\n" +
                          "TRUEPOS -1 -2 -0.3 0 0 0 3.000000 nohost 3\n"
                          "TRUEPOS 9 9 0 0 0 0 2.5 nohost 3\n";
  const Dataset d = ReadCarmen(WriteLog(dir, log));
  ASSERT_EQ(d.scans.size(), 3u);
  ASSERT_TRUE(d.scans[0].true_pose);
  EXPECT_EQ(*d.scans[0].true_pose, Pose2(5, 6, 0.7));
  EXPECT_FALSE(d.scans[1].true_pose);  // the TRUEPOS at 2.5 matches nothing
  ASSERT_TRUE(d.scans[2].true_pose);
  EXPECT_EQ(*d.scans[2].true_pose, Pose2(-1, -2, -0.3));
  EXPECT_FALSE(d.has_ground_truth());
}

TEST(CarmenReaderTest, ReadsCompressedLogsLikePlainOnes) {
  TempDir dir;
  std::string log;
  for (int i = 0; i < 200; ++i) log += OdomLine(i, i) + "\n" + FlaserLine(181, i + 0.5) + "\n";
  const Dataset plain = ReadCarmen(WriteLog(dir, log, "log.clf"));
  const Dataset gz = ReadCarmen(WriteLog(dir, GzipBytes(log), "log.clf.gz"));
  const Dataset bz = ReadCarmen(WriteLog(dir, Bzip2Bytes(log), "log.clf.bz2"));
  ASSERT_EQ(plain.scans.size(), 200u);
  for (const Dataset* d : {&gz, &bz}) {
    ASSERT_EQ(d->scans.size(), plain.scans.size());
    ASSERT_EQ(d->odometry.size(), plain.odometry.size());
    for (std::size_t i = 0; i < plain.scans.size(); ++i) {
      EXPECT_EQ(d->scans[i].ranges, plain.scans[i].ranges);
      EXPECT_EQ(d->scans[i].timestamp, plain.scans[i].timestamp);
    }
  }
}

struct MalformedCase {
  std::string name;
  std::string line;
  std::string expectation;  // part of the message saying what was expected
};

std::string FlaserWith(std::size_t n, std::size_t ranges, std::string_view trailing) {
  return fmt::format("FLASER {}{} {}", n, Ranges(ranges), trailing);
}

constexpr std::string_view kTrailing = "1 2 0.5 1.5 2.5 0.25 7.0 host 7.5";

std::vector<MalformedCase> MalformedCases() {
  return {
      {"FewerRanges", FlaserWith(180, 150, kTrailing), "FLASER: expected 180 ranges + 9 fields"},
      {"FewerRangesCountsFound", FlaserWith(180, 150, kTrailing), "found 159 fields"},
      {"ExtraField", FlaserWith(180, 180, std::string(kTrailing) + " 1"),
       "expected 180 ranges + 9 fields"},
      {"Truncated", "FLASER 180 1.0 2.0", "found 2 fields"},
      {"NoCount", "FLASER", "expected the number of ranges"},
      {"BadCount", "FLASER many 1 2", "num_readings is 'many', expected a count"},
      {"NonNumericRange", "FLASER 3 1.0 abc 2.0 " + std::string(kTrailing),
       "range 2 of 3 is 'abc', expected a finite number >= 0"},
      {"NegativeRange", "FLASER 3 1.0 2.0 -0.5 " + std::string(kTrailing),
       "range 3 of 3 is '-0.5'"},
      {"NanRange", "FLASER 3 nan 2.0 1.0 " + std::string(kTrailing), "range 1 of 3 is 'nan'"},
      {"InfPose", "FLASER 3 1 1 1 inf 2 0.5 1.5 2.5 0.25 7.0 host 7.5",
       "x is 'inf', expected a finite number"},
      {"NonNumericOdometry", "FLASER 3 1 1 1 1 2 0.5 1.5 two 0.25 7.0 host 7.5",
       "odom_y is 'two', expected a number"},
      {"BadTimestamp", "FLASER 3 1 1 1 1 2 0.5 1.5 2.5 0.25 7.0.1 host 7.5",
       "ipc_timestamp is '7.0.1'"},
      {"OdomTooShort", "ODOM 1 2 3 0 0 0 9.0", "ODOM: expected 9 fields"},
      {"OdomTooLong", "ODOM 1 2 3 0 0 0 9.0 host 9.0 1", "found 10"},
      {"OdomNan", "ODOM 1 2 nan 0 0 0 9.0 host 9.0", "theta is 'nan'"},
      {"TrueposTooShort", "TRUEPOS 1 2 3 4 5 6 7 host", "TRUEPOS: expected 9 fields"},
      {"ParamWithoutValue", "PARAM lonely", "PARAM: expected a name and a value"},
      {"BadRangeMaxParam", "PARAM laser_front_laser_max_range far nohost 0",
       "laser_front_laser_max_range is 'far', expected a positive number"},
      {"RobotLaserShortHead", "ROBOTLASER1 0 -1.5 3.1", "ROBOTLASER1: expected laser_type"},
      {"RobotLaserFewRanges", "ROBOTLASER1 0 -1.5 3.1 0.1 20 0.01 0 5 1 2 3",
       "expected 5 ranges + num_remissions"},
      {"RobotLaserMissingTail",
       "ROBOTLASER1 0 -1.5 3.1 0.1 20 0.01 0 2 1 2 1 0.5 1 2 3 4 5 6 7 8 9 10 11 12.0 host",
       "expected 1 remissions + 14 fields"},
      {"RobotLaserBadMaxRange",
       "ROBOTLASER1 0 -1.5 3.1 0.1 -20 0.01 0 1 1 0 1 2 3 4 5 6 7 8 9 10 11 12.0 host 13",
       "maximum_range is '-20', expected a positive number"},
  };
}

class CarmenMalformedTest : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(CarmenMalformedTest, FailsWithFileLineAndExpectation) {
  TempDir dir;
  const MalformedCase& c = GetParam();
  // Two good lines and a comment first, so the bad one is line 4.
  const auto path = WriteLog(dir,
                             "# header\n" + OdomLine(0, 1) + "\n" + FlaserLine(180, 1.5) + "\n" +
                                 c.line + "\n" + FlaserLine(180, 2) + "\n",
                             "bad_" + c.name + ".clf");
  const InputError e = ReadError(path);
  EXPECT_EQ(e.source(), path.string());
  EXPECT_EQ(e.line(), 4u);
  EXPECT_THAT(e.what(), HasSubstr(path.filename().string() + ":4: "));
  EXPECT_THAT(e.what(), HasSubstr(c.expectation));
}

INSTANTIATE_TEST_SUITE_P(Cases, CarmenMalformedTest, ::testing::ValuesIn(MalformedCases()),
                         [](const auto& info) { return info.param.name; });

TEST(CarmenReaderTest, LenientSkipsAndCountsMalformedLines) {
  TempDir dir;
  const std::string log = FlaserLine(180, 1) + "\n" + "FLASER 180 1 2 3\n" + OdomLine(0, 1) + "\n" +
                          "ODOM 1 2\n" + FlaserLine(180, 2) + "\n" +
                          "PARAM laser_front_laser_max_range x\n";
  const auto path = WriteLog(dir, log);
  EXPECT_EQ(ReadError(path).line(), 2u);
  CarmenReadStats stats;
  const Dataset d = ReadCarmen(path, {.lenient = true}, &stats);
  EXPECT_EQ(d.scans.size(), 2u);
  EXPECT_EQ(d.odometry.size(), 1u);
  EXPECT_TRUE(d.params.empty());
  EXPECT_EQ(stats.lines, 6u);
  EXPECT_EQ(stats.skipped, 3u);
  EXPECT_EQ(stats.first_skip_line, 2u);
  EXPECT_THAT(stats.first_skip_reason, StartsWith("FLASER: expected 180 ranges"));
}

TEST(CarmenReaderTest, MissingFileIsAnInputError) {
  TempDir dir;
  const InputError e = ReadError(dir / "absent.clf");
  EXPECT_THAT(e.what(), HasSubstr("absent.clf"));
}

// The real logs: counts from the data's README.
std::filesystem::path RealLog(const char* name) {
  return std::filesystem::path(EVOSLAM_DATA_DIR) / name;
}

TEST(CarmenReaderRealDataTest, IntelLog) {
  const auto path = RealLog("intel.clf.bz2");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  CarmenReadStats stats;
  const Dataset d = ReadCarmen(path, {}, &stats);
  EXPECT_EQ(d.scans.size(), 13631u);
  EXPECT_EQ(d.odometry.size(), 26915u);
  EXPECT_TRUE(d.rear_scans.empty());
  EXPECT_EQ(stats.skipped, 0u);
  std::size_t returns = 0;
  std::size_t beams = 0;
  for (const LaserScan& s : d.scans) {
    ASSERT_EQ(s.size(), 180u);
    ASSERT_NEAR(s.angle_increment, 1 * kDegree, 1e-12);
    for (std::size_t i = 0; i < s.size(); ++i) returns += s.is_return(i) ? 1 : 0;
    beams += s.size();
  }
  // 81.83 marks no return in this log; most beams do hit something indoors.
  EXPECT_LT(returns, beams);
  EXPECT_GT(returns, beams / 2);
  // First and last FLASER lines of the file.
  EXPECT_EQ(d.scans.front().ranges.front(), 1.07F);
  EXPECT_EQ(d.scans.back().timestamp, 976055548.624744);
  EXPECT_EQ(d.scans.back().odometry, Pose2(-50.883999, -35.825001, 2.538102));
}

TEST(CarmenReaderRealDataTest, MitCsailLogHas361Beams) {
  const auto path = RealLog("mit-csail.clf.bz2");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const Dataset d = ReadCarmen(path);
  ASSERT_EQ(d.scans.size(), 1988u);
  EXPECT_TRUE(d.odometry.empty());
  for (const LaserScan& s : d.scans) {
    ASSERT_EQ(s.size(), 361u);
    ASSERT_NEAR(s.angle(360), 90 * kDegree, 1e-12);
  }
}

TEST(CarmenReaderRealDataTest, AcesLog) {
  const auto path = RealLog("aces.clf.bz2");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const Dataset d = ReadCarmen(path);
  EXPECT_EQ(d.scans.size(), 7374u);
  EXPECT_EQ(d.scans.front().size(), 180u);
}

}  // namespace
}  // namespace evoslam
