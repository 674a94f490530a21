#include "common/io/carmen_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "common/io/carmen_reader.h"
#include "common/io/testing_files.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using io_testing::ReadBytes;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;

class Generator {
 public:
  float Range() { return std::uniform_real_distribution<float>(0.0F, 80.0F)(rng_); }
  double Value() { return std::uniform_real_distribution<double>(-100.0, 100.0)(rng_); }
  Pose2 Pose() {
    return {Value(), Value(), std::uniform_real_distribution<double>(-kPi, kPi)(rng_)};
  }

 private:
  std::mt19937 rng_{7};
};

LaserScan MakeScan(Generator& g, std::size_t beams, double timestamp, LaserMessage message) {
  LaserScan scan;
  scan.timestamp = timestamp;
  scan.logger_timestamp = timestamp + 0.25;
  scan.hostname = "host" + std::to_string(beams);
  scan.message = message;
  scan.angle_min = -kPi / 2;
  scan.angle_increment =
      beams % 2 == 1 ? kPi / static_cast<double>(beams - 1) : kPi / static_cast<double>(beams);
  scan.range_max = 50.0;
  for (std::size_t i = 0; i < beams; ++i) scan.ranges.push_back(g.Range());
  scan.pose = g.Pose();
  scan.odometry = g.Pose();
  return scan;
}

// A scan only ROBOTLASER can hold: 90 beams over 89 deg from -30 deg.
LaserScan MakeOddScan(Generator& g, double timestamp, LaserMessage message) {
  LaserScan scan = MakeScan(g, 90, timestamp, message);
  scan.angle_min = -30.0 * kPi / 180.0;
  scan.angle_increment = kPi / 180.0;
  scan.range_max = 30.0;
  scan.odometry = scan.pose;  // ROBOTLASER carries one pose
  return scan;
}

OdometryReading MakeOdometry(Generator& g, double timestamp) {
  OdometryReading odom;
  odom.timestamp = timestamp;
  odom.logger_timestamp = timestamp + 0.125;
  odom.pose = g.Pose();
  odom.tv = g.Value();
  odom.rv = g.Value();
  odom.accel = g.Value();
  return odom;
}

Dataset MakeDataset() {
  Generator g;
  Dataset d;
  d.params = {{"robot_frontlaser_offset", "0.0"},
              {"robot_use_laser", "on"},
              {"description", "two words 3"}};
  d.odometry = {MakeOdometry(g, 100.000001), MakeOdometry(g, 100.5), MakeOdometry(g, 101.75)};
  d.scans = {MakeScan(g, 180, 100.25, LaserMessage::kFront),
             MakeScan(g, 181, 100.75, LaserMessage::kFront),
             MakeOddScan(g, 101.0, LaserMessage::kRobotLaser),
             MakeScan(g, 361, 101.5, LaserMessage::kFront)};
  d.scans[0].true_pose = g.Pose();
  d.scans[3].true_pose = g.Pose();
  d.rear_scans = {MakeScan(g, 180, 100.3, LaserMessage::kRear),
                  MakeOddScan(g, 101.6, LaserMessage::kRear)};
  d.rear_scans[0].true_pose = g.Pose();
  return d;
}

void ExpectSameScans(const std::vector<LaserScan>& actual, const std::vector<LaserScan>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE("scan " + std::to_string(i));
    const LaserScan& a = actual[i];
    const LaserScan& e = expected[i];
    EXPECT_EQ(a.message, e.message);
    EXPECT_EQ(a.timestamp, e.timestamp);
    EXPECT_EQ(a.logger_timestamp, e.logger_timestamp);
    EXPECT_EQ(a.hostname, e.hostname);
    EXPECT_NEAR(a.angle_min, e.angle_min, 1e-12);
    EXPECT_NEAR(a.angle_increment, e.angle_increment, 1e-12);
    EXPECT_EQ(a.range_min, e.range_min);
    EXPECT_EQ(a.range_max, e.range_max);
    EXPECT_EQ(a.ranges, e.ranges);
    EXPECT_EQ(a.pose, e.pose);
    EXPECT_EQ(a.odometry, e.odometry);
    EXPECT_EQ(a.true_pose, e.true_pose);
  }
}

void ExpectSameDataset(const Dataset& actual, const Dataset& expected) {
  EXPECT_EQ(actual.params, expected.params);
  ExpectSameScans(actual.scans, expected.scans);
  ExpectSameScans(actual.rear_scans, expected.rear_scans);
  ASSERT_EQ(actual.odometry.size(), expected.odometry.size());
  for (std::size_t i = 0; i < expected.odometry.size(); ++i) {
    const OdometryReading& a = actual.odometry[i];
    const OdometryReading& e = expected.odometry[i];
    EXPECT_EQ(a.timestamp, e.timestamp);
    EXPECT_EQ(a.logger_timestamp, e.logger_timestamp);
    EXPECT_EQ(a.hostname, e.hostname);
    EXPECT_EQ(a.pose, e.pose);
    EXPECT_EQ(a.tv, e.tv);
    EXPECT_EQ(a.rv, e.rv);
    EXPECT_EQ(a.accel, e.accel);
  }
}

std::vector<std::string> Lines(const std::filesystem::path& path) {
  std::istringstream in(ReadBytes(path));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string FirstWord(const std::string& line) { return line.substr(0, line.find(' ')); }

TEST(CarmenWriterTest, RoundTripsEveryMessageKind) {
  TempDir dir;
  const Dataset original = MakeDataset();
  WriteCarmen(original, dir / "out.clf");
  ExpectSameDataset(ReadCarmen(dir / "out.clf"), original);
}

TEST(CarmenWriterTest, ChoosesMessagesAndOrdersThemByTime) {
  TempDir dir;
  WriteCarmen(MakeDataset(), dir / "out.clf");
  std::vector<std::string> messages;
  for (const std::string& line : Lines(dir / "out.clf")) {
    if (line.empty() || line[0] == '#') continue;
    messages.push_back(FirstWord(line));
  }
  // Timestamps: odom 100.000001, scan 100.25 (+truth), rear 100.3 (+truth), odom 100.5,
  // scan 100.75, robot-laser scan 101.0, scan 101.5 (+truth), rear robot-laser 101.6, odom 101.75.
  EXPECT_THAT(messages,
              ::testing::ElementsAre("PARAM", "PARAM", "PARAM", "ODOM", "FLASER", "TRUEPOS",
                                     "RLASER", "TRUEPOS", "ODOM", "FLASER", "ROBOTLASER1", "FLASER",
                                     "TRUEPOS", "ROBOTLASER2", "ODOM"));
}

TEST(CarmenWriterTest, KeepsEachStreamsOrderWhenTimestampsAreNotSorted) {
  TempDir dir;
  Generator g;
  Dataset d;
  d.scans = {MakeScan(g, 180, 5.0, LaserMessage::kFront),
             MakeScan(g, 180, 3.0, LaserMessage::kFront),
             MakeScan(g, 180, 4.0, LaserMessage::kFront)};
  d.odometry = {MakeOdometry(g, 4.5), MakeOdometry(g, 1.0)};
  WriteCarmen(d, dir / "out.clf");
  ExpectSameDataset(ReadCarmen(dir / "out.clf"), d);
}

TEST(CarmenWriterTest, GeometryFlaserCannotHoldGoesAsRobotLaser) {
  TempDir dir;
  Generator g;
  Dataset d;
  d.scans = {MakeOddScan(g, 1.0, LaserMessage::kFront),
             MakeScan(g, 180, 2.0, LaserMessage::kFront)};
  d.scans[1].range_max = 20.0;  // not what a FLASER line would read back as
  d.scans[1].odometry = d.scans[1].pose;
  WriteCarmen(d, dir / "out.clf");
  const Dataset back = ReadCarmen(dir / "out.clf");
  ASSERT_EQ(back.scans.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.scans[i].message, LaserMessage::kRobotLaser);
    EXPECT_NEAR(back.scans[i].angle_min, d.scans[i].angle_min, 1e-12);
    EXPECT_NEAR(back.scans[i].angle_increment, d.scans[i].angle_increment, 1e-12);
    EXPECT_EQ(back.scans[i].range_max, d.scans[i].range_max);
    EXPECT_EQ(back.scans[i].ranges, d.scans[i].ranges);
    EXPECT_EQ(back.scans[i].pose, d.scans[i].pose);
  }
}

TEST(CarmenWriterTest, RangeMaxParamLetsFlaserCarryOtherRanges) {
  TempDir dir;
  Generator g;
  Dataset d;
  d.params = {{"laser_front_laser_max_range", "20"}};
  d.scans = {MakeScan(g, 361, 2.0, LaserMessage::kFront)};
  d.scans[0].range_max = 20.0;
  // An increment computed in float is still FLASER's geometry.
  d.scans[0].angle_increment = static_cast<float>(kPi / 360.0);
  WriteCarmen(d, dir / "out.clf");
  EXPECT_EQ(FirstWord(Lines(dir / "out.clf").back()), "FLASER");
  const Dataset back = ReadCarmen(dir / "out.clf");
  EXPECT_EQ(back.scans[0].range_max, 20.0);
  EXPECT_EQ(back.scans[0].message, LaserMessage::kFront);
}

TEST(CarmenWriterTest, MillimetreRangesReadBackExactly) {
  TempDir dir;
  Generator g;
  Dataset d;
  d.scans = {MakeScan(g, 181, 1.0, LaserMessage::kFront)};
  for (std::size_t i = 0; i < 181; ++i) {
    d.scans[0].ranges[i] =
        std::strtof(std::to_string(0.001 * static_cast<double>(i * 337)).c_str(), nullptr);
  }
  WriteCarmen(d, dir / "out.clf");
  EXPECT_EQ(ReadCarmen(dir / "out.clf").scans[0].ranges, d.scans[0].ranges);
}

TEST(CarmenWriterTest, RejectsWhatCarmenCannotHold) {
  TempDir dir;
  const auto expect_error = [&](const Dataset& d, const std::string& part) {
    try {
      WriteCarmen(d, dir / "bad.clf");
      ADD_FAILURE() << "expected an Error for " << part;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("bad.clf"));
      EXPECT_THAT(e.what(), HasSubstr(part));
    }
  };
  Generator g;
  Dataset d;
  d.scans = {MakeScan(g, 180, 1.0, LaserMessage::kFront)};
  Dataset infinite = d;
  infinite.scans[0].ranges[7] = std::numeric_limits<float>::infinity();
  expect_error(infinite, "beam 7");
  Dataset negative = d;
  negative.scans[0].ranges[3] = -1.0F;
  expect_error(negative, "beam 3");
  Dataset spaced = d;
  spaced.scans[0].hostname = "my host";
  expect_error(spaced, "hostname");
  Dataset bad_param = d;
  bad_param.params = {{"two words", "1"}};
  expect_error(bad_param, "PARAM");
  Dataset nan_time = d;
  nan_time.scans[0].timestamp = std::nan("");
  expect_error(nan_time, "timestamp");
}

TEST(CarmenWriterTest, UnwritablePathIsAnErrorNamingIt) {
  TempDir dir;
  const auto path = dir / "missing_folder" / "out.clf";
  try {
    WriteCarmen(MakeDataset(), path);
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
}

TEST(CarmenWriterRealDataTest, IntelLogRoundTrips) {
  const auto path = std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  TempDir dir;
  const Dataset original = ReadCarmen(path);
  WriteCarmen(original, dir / "intel.clf");
  ExpectSameDataset(ReadCarmen(dir / "intel.clf"), original);
}

}  // namespace
}  // namespace evoslam
