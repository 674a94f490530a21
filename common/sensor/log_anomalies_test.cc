#include "common/sensor/log_anomalies.h"

#include <gtest/gtest.h>

#include <vector>

namespace evoslam {
namespace {

// Scans 5 cm apart along x, one a second.
std::vector<LaserScan> Drive(std::size_t n) {
  std::vector<LaserScan> scans(n);
  for (std::size_t i = 0; i < n; ++i) {
    scans[i].timestamp = static_cast<double>(i);
    scans[i].odometry = Pose2(0.05 * static_cast<double>(i), 0.0, 0.0);
  }
  return scans;
}

TEST(LogAnomaliesTest, AnEvenDriveHasNone) {
  const LogAnomalies a = FindLogAnomalies(Drive(100));
  EXPECT_NEAR(a.typical_step_m, 0.05, 1e-12);
  EXPECT_TRUE(a.jumps.empty());
  EXPECT_TRUE(a.reversals.empty());
}

TEST(LogAnomaliesTest, AJumpIsNamedByTheScansEitherSideOfIt) {
  std::vector<LaserScan> scans = Drive(100);
  for (std::size_t i = 40; i < scans.size(); ++i)
    scans[i].odometry = Pose2(20.0, 0.0, 0.0) * scans[i].odometry;
  const LogAnomalies a = FindLogAnomalies(scans);
  ASSERT_EQ(a.jumps.size(), 1u);
  EXPECT_EQ(a.jumps[0].from, 39u);
  EXPECT_NEAR(a.jumps[0].length_m, 20.05, 1e-9);
}

TEST(LogAnomaliesTest, AJumpInsideAStandstillIsFoundWhereItHappened) {
  // The robot stands still, but scan 9's odometry reads a kilometre away.
  std::vector<LaserScan> scans(12);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    scans[i].timestamp = static_cast<double>(i);
    scans[i].odometry = Pose2(i >= 9 ? 1000.0 : 0.0, 0.0, 0.0);
  }
  const LogAnomalies a = FindLogAnomalies(scans);
  EXPECT_EQ(a.typical_step_m, 0.0);
  ASSERT_EQ(a.jumps.size(), 1u);
  EXPECT_EQ(a.jumps[0].from, 8u);
}

TEST(LogAnomaliesTest, StepsFasterThanThePaceButShortAreNoJumps) {
  std::vector<LaserScan> scans = Drive(100);
  // A 0.9 m step is 18 times the pace and below the metre every jump must reach.
  for (std::size_t i = 50; i < scans.size(); ++i)
    scans[i].odometry = Pose2(0.85, 0.0, 0.0) * scans[i].odometry;
  EXPECT_TRUE(FindLogAnomalies(scans).jumps.empty());
}

TEST(LogAnomaliesTest, TimestampsThatGoBackAreReportedAtTheirScan) {
  std::vector<LaserScan> scans = Drive(20);
  for (std::size_t i = 7; i < scans.size(); ++i) scans[i].timestamp -= 58.43;
  const LogAnomalies a = FindLogAnomalies(scans);
  ASSERT_EQ(a.reversals.size(), 1u);
  EXPECT_EQ(a.reversals[0].scan, 7u);
  EXPECT_NEAR(a.reversals[0].back_s, 57.43, 1e-9);
}

}  // namespace
}  // namespace evoslam
