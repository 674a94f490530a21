#include "common/sensor/odometry_stalls.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

const Eigen::Vector3d kCube(0.1, 0.1, 0.05);  // the local search's default cube

// Scans at `times`, the odometry moving 1.25 m/s along x and turning 0.5 rad/s from heading 3 rad
// (so that it passes pi).
std::vector<LaserScan> Drive(const std::vector<double>& times) {
  std::vector<LaserScan> scans(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    scans[i].timestamp = times[i];
    scans[i].odometry = Pose2(1.25 * times[i], 0.0, 3.0 + 0.5 * times[i]);
  }
  return scans;
}

// Scans [first, last] repeat scan first - 1's odometry, as when the messages were held up.
void Stall(std::vector<LaserScan>& scans, std::size_t first, std::size_t last) {
  for (std::size_t k = first; k <= last; ++k) scans[k].odometry = scans[first - 1].odometry;
}

// Scans [first, last] repeat scan first - 1's position while their headings read on.
void StallThePosition(std::vector<LaserScan>& scans, std::size_t first, std::size_t last) {
  for (std::size_t k = first; k <= last; ++k) {
    scans[k].odometry = Pose2(scans[first - 1].odometry.translation(), scans[k].odometry.theta());
  }
}

// Whether `stalls` is a single stall over scans [first, last], its heading held or read on.
testing::AssertionResult OneStall(const std::vector<OdometryStall>& stalls, std::size_t first,
                                  std::size_t last, bool heading_held) {
  if (stalls.size() != 1) return testing::AssertionFailure() << stalls.size() << " stalls";
  const OdometryStall& s = stalls[0];
  if (s.first != first || s.last != last || s.heading_held != heading_held) {
    return testing::AssertionFailure() << "scans " << s.first << " to " << s.last
                                       << (s.heading_held ? ", heading held" : ", heading read on");
  }
  return testing::AssertionSuccess();
}

TEST(FindOdometryStallsTest, FindsRepeatsEndedByACatchUpTheCubeCannotAbsorb) {
  std::vector<LaserScan> scans = Drive({0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6});
  Stall(scans, 3, 6);
  const std::vector<OdometryStall> stalls = FindOdometryStalls(scans, kCube);
  ASSERT_TRUE(OneStall(stalls, 3, 6, true));
  EXPECT_NEAR(stalls[0].catch_up.theta(), 0.5, 1e-12);  // 1 s of turning at 0.5 rad/s
  EXPECT_NEAR(stalls[0].catch_up.translation().norm(), 1.25, 1e-12);
}

TEST(FindOdometryStallsTest, LeavesAStillRobotAndARunAtTheEndAlone) {
  std::vector<LaserScan> scans(8);
  for (std::size_t i = 0; i < scans.size(); ++i) scans[i].timestamp = 0.2 * i;
  // Standing still for scans 0 to 4, then creeping 2 cm and 1 degree a scan; the last two repeat.
  for (std::size_t i = 5; i < 7; ++i) {
    scans[i].odometry = scans[i - 1].odometry * Pose2(0.02, 0.0, 0.0175);
  }
  scans[7].odometry = scans[6].odometry;
  EXPECT_TRUE(FindOdometryStalls(scans, kCube).empty());
  // The same creep counts once the cube is tighter than it.
  EXPECT_EQ(FindOdometryStalls(scans, Eigen::Vector3d(0.01, 0.01, 0.01)).size(), 1u);
}

TEST(FindOdometryStallsTest, FindsAPositionHeldWhileTheHeadingReadOn) {
  std::vector<LaserScan> scans = Drive({0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6});
  StallThePosition(scans, 3, 6);
  const std::vector<OdometryStall> stalls = FindOdometryStalls(scans, kCube);
  ASSERT_TRUE(OneStall(stalls, 3, 6, false));
  EXPECT_NEAR(stalls[0].catch_up.translation().norm(), 1.25, 1e-12);
}

TEST(FindOdometryStallsTest, LeavesATurnOnTheSpotAlone) {
  // Turning 0.3 rad a scan on the spot for scans 1 to 5, then driving off 5 cm a scan.
  std::vector<LaserScan> scans(9);
  for (std::size_t i = 1; i < scans.size(); ++i) {
    scans[i].timestamp = 0.2 * static_cast<double>(i);
    scans[i].odometry = scans[i - 1].odometry * (i <= 5 ? Pose2(0.0, 0.0, 0.3) : Pose2(0.05, 0, 0));
  }
  EXPECT_TRUE(FindOdometryStalls(scans, kCube).empty()) << "1.5 rad turned, but read as it went";
  // Its position is held all the same, as a cube of nothing shows.
  const std::vector<OdometryStall> held = FindOdometryStalls(scans, Eigen::Vector3d::Zero());
  ASSERT_TRUE(OneStall(held, 1, 5, false));
}

TEST(FindOdometryStallsTest, FindsReadingsHeldUpWhileTurningOnTheSpot) {
  // Turning 0.02 rad a scan on the spot; the readings of scans 4 to 6 repeat scan 3's, and scan 7
  // catches up 0.08 rad.
  std::vector<LaserScan> scans(10);
  for (std::size_t i = 1; i < scans.size(); ++i) {
    scans[i].timestamp = 0.2 * static_cast<double>(i);
    scans[i].odometry = scans[i - 1].odometry * (i < 8 ? Pose2(0.0, 0.0, 0.02) : Pose2(0.05, 0, 0));
  }
  Stall(scans, 4, 6);
  const std::vector<OdometryStall> stalls = FindOdometryStalls(scans, kCube);
  ASSERT_TRUE(OneStall(stalls, 4, 6, true));
  EXPECT_NEAR(stalls[0].catch_up.theta(), 0.08, 1e-12);
}

TEST(FindOdometryStallsTest, AHeldPositionIsOneStallThoughItsHeadingRepeatsOnce) {
  std::vector<LaserScan> scans = Drive({0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6});
  StallThePosition(scans, 3, 6);
  scans[5].odometry = scans[4].odometry;
  const std::vector<OdometryStall> stalls = FindOdometryStalls(scans, kCube);
  ASSERT_TRUE(OneStall(stalls, 3, 6, false));
  // The repeated reading is there all the same, as what `evoslam info` counts.
  const std::vector<OdometryStall> repeats = FindRepeatedReadings(scans);
  ASSERT_TRUE(OneStall(repeats, 5, 5, true));
}

TEST(FillOdometryStallsTest, SpreadsThePositionAndKeepsTheHeadingsThatReadOn) {
  const std::vector<LaserScan> truth = Drive({0.0, 0.21, 0.4, 0.63, 0.8, 1.05, 1.2, 1.41, 1.6});
  std::vector<LaserScan> scans = truth;
  StallThePosition(scans, 3, 6);
  // Headings that a spread between scans 2 and 7 would not give back.
  for (std::size_t k = 3; k <= 6; ++k) scans[k].odometry = scans[k].odometry * Pose2(0, 0, 0.1);
  const std::vector<LaserScan> read = scans;
  FillOdometryStalls(scans, FindOdometryStalls(scans, kCube));
  for (std::size_t i = 0; i < scans.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(scans[i].odometry.x(), truth[i].odometry.x(), 1e-12);
    EXPECT_NEAR(scans[i].odometry.y(), truth[i].odometry.y(), 1e-12);
    EXPECT_EQ(scans[i].odometry.theta(), read[i].odometry.theta());
  }
}

TEST(FillOdometryStallsTest, SpreadsTheCatchUpOverTheStallByTime) {
  // Uneven scan times, as a logger's are. The drive's odometry changes at a constant rate in
  // time, so the filled readings are its own.
  const std::vector<LaserScan> truth = Drive({0.0, 0.21, 0.4, 0.63, 0.8, 1.05, 1.2, 1.41, 1.6});
  std::vector<LaserScan> scans = truth;
  Stall(scans, 3, 6);
  FillOdometryStalls(scans, FindOdometryStalls(scans, kCube));
  for (std::size_t i = 0; i < scans.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(scans[i].odometry.x(), truth[i].odometry.x(), 1e-12);
    EXPECT_NEAR(WrapAngle(scans[i].odometry.theta() - truth[i].odometry.theta()), 0.0, 1e-12);
  }
}

TEST(FillOdometryStallsTest, SpreadsByScanWhereTheTimestampsDoNotIncrease) {
  std::vector<LaserScan> scans = Drive({0.0, 0.2, 0.4, 0.6, 0.8});
  Stall(scans, 2, 3);
  for (LaserScan& scan : scans) scan.timestamp = 7.0;
  FillOdometryStalls(scans, FindOdometryStalls(scans, kCube));
  EXPECT_NEAR(scans[2].odometry.x(), 0.5, 1e-12);  // a third of the way from 0.25 to 1.0
  EXPECT_NEAR(scans[3].odometry.x(), 0.75, 1e-12);
}

TEST(FillOdometryStallsTest, RefusesAStallWithoutAReadingEitherSide) {
  std::vector<LaserScan> scans = Drive({0.0, 0.2, 0.4});
  const OdometryStall at_start{0, 1, Pose2()};
  const OdometryStall at_end{1, 2, Pose2()};
  EXPECT_THROW(FillOdometryStalls(scans, std::vector<OdometryStall>{at_start}), Error);
  EXPECT_THROW(FillOdometryStalls(scans, std::vector<OdometryStall>{at_end}), Error);
}

TEST(RunWithOdometryStallsFilledTest, RunsOverTheLogItselfWhenNothingStalled) {
  Dataset log{.source = "drive",
              .scans = Drive({0.0, 0.2, 0.4}),
              .rear_scans = {},
              .odometry = {},
              .params = {}};
  const Dataset* seen = RunWithOdometryStallsFilled(log, std::vector<OdometryStall>{},
                                                    [](const Dataset& d) { return &d; });
  EXPECT_EQ(seen, &log);  // no copy
}

TEST(RunWithOdometryStallsFilledTest, RunsOverAFilledCopyAndLeavesTheLogAsItWas) {
  const std::vector<LaserScan> truth = Drive({0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6});
  Dataset log{.source = "drive", .scans = truth, .rear_scans = {}, .odometry = {}, .params = {}};
  Stall(log.scans, 3, 6);
  const std::vector<OdometryStall> stalls = FindOdometryStalls(log.scans, kCube);
  ASSERT_EQ(stalls.size(), 1u);
  const Pose2 fourth = RunWithOdometryStallsFilled(log, stalls, [&](const Dataset& d) {
    EXPECT_NE(&d, &log);
    EXPECT_EQ(d.source, log.source);
    return d.scans[4].odometry;
  });
  EXPECT_NEAR(fourth.x(), truth[4].odometry.x(), 1e-9);
  EXPECT_NEAR(fourth.theta(), truth[4].odometry.theta(), 1e-9);
  EXPECT_EQ(log.scans[4].odometry.x(), log.scans[2].odometry.x());  // the log keeps its stall
}

}  // namespace
}  // namespace evoslam
