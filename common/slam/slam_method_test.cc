#include "common/slam/slam_method.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/sim/simulator.h"
#include "common/sim/world.h"

namespace evoslam {
namespace {

std::vector<StampedPose> TruePoses(const Dataset& log) {
  std::vector<StampedPose> poses;
  for (const LaserScan& s : log.scans) poses.push_back({s.timestamp, *s.true_pose});
  return poses;
}

TEST(ScansToMapTest, IsMaxScansWhenTheLogHasThatMany) {
  Dataset log;
  log.scans.resize(10);
  proto::SlamParams params;
  EXPECT_EQ(ScansToMap(log, params), 10u);
  params.set_max_scans(4);
  EXPECT_EQ(ScansToMap(log, params), 4u);
  params.set_max_scans(40);
  EXPECT_EQ(ScansToMap(log, params), 10u);
}

// A run that spans more than a map of 5 cm cells can hold (2^26 cells, 8192 on a side, 410 m)
// still gets its map, at 10 cm, with every return on it.
TEST(OccupancyGridAtPosesTest, ARunTooWideForTheCellsGetsACoarserMap) {
  SimulationOptions sim;
  sim.max_scans = 30;
  const Dataset log = Simulate(BuiltinWorld("s-corridor"), sim);
  std::vector<StampedPose> poses = TruePoses(log);
  EXPECT_DOUBLE_EQ(OccupancyGridAtPoses(log, poses, 0.05).resolution(), 0.05);
  const Pose2 far(415.0, 415.0, 0.0);
  poses.back().pose = far;
  const OccupancyGrid map = OccupancyGridAtPoses(log, poses, 0.05);
  EXPECT_DOUBLE_EQ(map.resolution(), 0.1);
  for (const Eigen::Vector2d& end : ReturnPoints(log.scans.back())) {
    ASSERT_TRUE(map.WorldToCell(far * end)) << "every return lies on the map";
  }
  // Only the poses given are drawn.
  poses.resize(10);
  const OccupancyGrid part = OccupancyGridAtPoses(log, poses, 0.05);
  EXPECT_LT(part.width() * part.height(), map.width() * map.height());
}

}  // namespace
}  // namespace evoslam
