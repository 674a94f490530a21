#include "common/io/trajectory_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "common/io/testing_files.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using io_testing::Bzip2Bytes;
using io_testing::ReadBytes;
using io_testing::WriteBytes;
using ::testing::HasSubstr;

std::vector<StampedPose> SomePoses() {
  std::vector<StampedPose> poses;
  for (int i = 0; i < 50; ++i) {
    const double theta = -3.1 + 0.125 * i;  // crosses 0 and comes close to +-pi
    poses.push_back({976052905.167303 + 0.25 * i, Pose2(12.345678 * i - 200.0, -0.001 * i, theta)});
  }
  poses.push_back({976052999.0, Pose2(1, 2, std::numbers::pi)});
  return poses;
}

void ExpectNearPoses(const std::vector<StampedPose>& actual,
                     const std::vector<StampedPose>& expected, double tolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    // Timestamps are written to the microsecond.
    EXPECT_NEAR(actual[i].timestamp, expected[i].timestamp, 1e-6) << i;
    EXPECT_NEAR(actual[i].pose.x(), expected[i].pose.x(), tolerance) << i;
    EXPECT_NEAR(actual[i].pose.y(), expected[i].pose.y(), tolerance) << i;
    // Compare headings on the circle: pi and -pi are the same heading.
    EXPECT_NEAR(WrapAngle(actual[i].pose.theta() - expected[i].pose.theta()), 0.0, tolerance) << i;
  }
}

TEST(TrajectoryIoTest, TextRoundTrip) {
  TempDir dir;
  const auto poses = SomePoses();
  WriteTrajectoryText(poses, dir / "t.txt");
  ExpectNearPoses(ReadTrajectory(dir / "t.txt"), poses, 1e-6);
}

TEST(TrajectoryIoTest, TumRoundTrip) {
  TempDir dir;
  const auto poses = SomePoses();
  WriteTrajectoryTum(poses, dir / "t.tum");
  ExpectNearPoses(ReadTrajectory(dir / "t.tum"), poses, 1e-6);
}

TEST(TrajectoryIoTest, TumLinesHoldTheHeadingQuaternion) {
  TempDir dir;
  const std::vector<StampedPose> poses = {{1.5, Pose2(3, 4, std::numbers::pi / 2)}};
  WriteTrajectoryTum(poses, dir / "t.tum");
  std::vector<double> values;
  std::istringstream in(ReadBytes(dir / "t.tum"));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    for (double v = 0; fields >> v;) values.push_back(v);
  }
  ASSERT_EQ(values.size(), 8u);
  const double h = std::sqrt(0.5);
  EXPECT_EQ(values[0], 1.5);
  EXPECT_EQ(values[1], 3.0);
  EXPECT_EQ(values[2], 4.0);
  EXPECT_EQ(values[3], 0.0);
  EXPECT_EQ(values[4], 0.0);
  EXPECT_EQ(values[5], 0.0);
  EXPECT_NEAR(values[6], h, 1e-8);
  EXPECT_NEAR(values[7], h, 1e-8);
}

TEST(TrajectoryIoTest, ReadsCommentsUnnormalisedQuaternionsAndCompressedFiles) {
  TempDir dir;
  // Yaw of 90 deg as a quaternion scaled by 2; x and y rotations would be dropped.
  WriteBytes(dir / "t.tum.bz2", Bzip2Bytes("# TUM\n\n1.0 1 2 0 0 0 1.41421356 1.41421356\n"
                                           "2.0 3 4 0.5 0 0 0 1\n"));
  const auto poses = ReadTrajectory(dir / "t.tum.bz2");
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_NEAR(poses[0].pose.theta(), std::numbers::pi / 2, 1e-8);
  EXPECT_EQ(poses[1].pose, Pose2(3, 4, 0));
}

InputError ReadError(const std::filesystem::path& path) {
  try {
    ReadTrajectory(path);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", 0, "");
}

TEST(TrajectoryIoTest, MalformedLinesNameFileLineAndExpectation) {
  TempDir dir;
  WriteBytes(dir / "five.txt", "# t x y theta\n1 2 3 4\n1 2 3 4 5\n");
  InputError e = ReadError(dir / "five.txt");
  EXPECT_EQ(e.line(), 3u);
  EXPECT_THAT(e.what(), HasSubstr("five.txt:3:"));
  EXPECT_THAT(e.what(), HasSubstr("expected 4 fields like line 2, found 5"));

  WriteBytes(dir / "seven.txt", "1 2 3 4 5 6 7\n");
  e = ReadError(dir / "seven.txt");
  EXPECT_EQ(e.line(), 1u);
  EXPECT_THAT(e.what(), HasSubstr("expected 4 fields (t x y theta) or 8 fields"));

  WriteBytes(dir / "word.txt", "1 2 3 4\n2 2 north 4\n");
  e = ReadError(dir / "word.txt");
  EXPECT_EQ(e.line(), 2u);
  EXPECT_THAT(e.what(), HasSubstr("field 3 is 'north', expected a finite number"));

  WriteBytes(dir / "zero.tum", "1 2 3 0 0 0 0 0\n");
  e = ReadError(dir / "zero.tum");
  EXPECT_THAT(e.what(), HasSubstr("zero.tum:1: quaternion"));
}

TEST(TrajectoryIoTest, UnwritablePathIsAnError) {
  TempDir dir;
  const auto path = dir / "no" / "t.txt";
  EXPECT_THROW(WriteTrajectoryText(SomePoses(), path), Error);
  EXPECT_THROW(WriteTrajectoryTum(SomePoses(), path), Error);
}

}  // namespace
}  // namespace evoslam
