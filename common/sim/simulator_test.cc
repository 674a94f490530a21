#include "common/sim/simulator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/io/carmen_reader.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using ::testing::HasSubstr;

SimulationOptions Noiseless() {
  SimulationOptions options;
  options.noise.odometry = {0.0, 0.0, 0.0, 0.0};
  return options;
}

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SimulatorTest, LogsTheRouteLikeTheExperiment) {
  const World world = BuiltinWorld("s-corridor");
  const Dataset d = Simulate(world, {});
  EXPECT_NEAR(static_cast<double>(d.scans.size()), 219.0, 11.0);
  ASSERT_EQ(d.odometry.size(), d.scans.size());
  EXPECT_TRUE(d.has_ground_truth());
  EXPECT_THAT(d.params, ::testing::Contains(
                            std::pair<std::string, std::string>("robot_front_laser_max", "8")));
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    const LaserScan& s = d.scans[i];
    ASSERT_EQ(s.size(), 361u);
    EXPECT_DOUBLE_EQ(s.timestamp, kSimulationEpoch + 0.2 * static_cast<double>(i));
    EXPECT_EQ(d.odometry[i].timestamp, s.timestamp);
    EXPECT_EQ(d.odometry[i].pose, s.odometry);
    EXPECT_EQ(s.pose, s.odometry);  // a raw log states the odometry
    EXPECT_EQ(s.range_max, 8.0);
    EXPECT_NEAR(s.field_of_view(), std::numbers::pi, 1e-12);
  }
  // The robot starts at the route's first waypoint, heading along its first leg.
  EXPECT_TRUE(d.scans.front().true_pose->translation().isApprox(world.waypoints.front()));
  EXPECT_EQ(d.scans.front().odometry, *d.scans.front().true_pose);
}

TEST(SimulatorTest, NoiselessRangesAreRayCastsFromTheTruePose) {
  const World world = BuiltinWorld("office-boxes");
  SimulationOptions options = Noiseless();
  options.max_scans = 40;
  const Dataset d = Simulate(world, options);
  ASSERT_EQ(d.scans.size(), 40u);
  int returns = 0;
  for (const LaserScan& s : d.scans) {
    EXPECT_EQ(s.odometry, *s.true_pose);
    for (std::size_t b = 0; b < s.size(); ++b) {
      const double expected =
          world.map.CastRay(s.true_pose->translation(), s.true_pose->theta() + s.angle(b), 8.0);
      ASSERT_EQ(s.ranges[b], static_cast<float>(expected));
      returns += s.is_return(b);
    }
  }
  EXPECT_GT(returns, 40 * 361 / 2);  // a 10 m room: most beams meet a wall within 8 m
}

TEST(SimulatorTest, SameSeedSameDatasetOtherSeedDiffers) {
  const World world = BuiltinWorld("static-objects");
  SimulationOptions options;
  options.noise.uniform_bandwidth = 0.2;
  options.noise.pedestrians = 3;
  options.max_scans = 60;
  const Dataset a = Simulate(world, options);
  const Dataset b = Simulate(world, options);
  options.seed = 2;
  const Dataset c = Simulate(world, options);
  ASSERT_EQ(a.scans.size(), b.scans.size());
  bool differs = false;
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    EXPECT_EQ(a.scans[i].ranges, b.scans[i].ranges);
    EXPECT_EQ(a.scans[i].odometry, b.scans[i].odometry);
    EXPECT_EQ(a.scans[i].true_pose, c.scans[i].true_pose);  // the route does not depend on it
    differs = differs || a.scans[i].ranges != c.scans[i].ranges ||
              !(a.scans[i].odometry == c.scans[i].odometry);
  }
  EXPECT_TRUE(differs);
}

TEST(SimulatorTest, UniformNoiseStaysWithinItsBand) {
  const World world = BuiltinWorld("empty-room");
  SimulationOptions options = Noiseless();
  options.max_scans = 100;
  const Dataset clean = Simulate(world, options);
  options.noise.uniform_bandwidth = 0.2;
  const Dataset noisy = Simulate(world, options);
  double sum = 0.0;
  double low = 1.0;
  double high = -1.0;
  int n = 0;
  for (std::size_t i = 0; i < clean.scans.size(); ++i) {
    for (std::size_t b = 0; b < clean.scans[i].size(); ++b) {
      const double truth = clean.scans[i].ranges[b];
      if (truth < 0.2 || truth > 7.8) continue;  // clamping would bias these
      const double r = noisy.scans[i].ranges[b] - truth;
      sum += r;
      low = std::min(low, r);
      high = std::max(high, r);
      ++n;
    }
  }
  ASSERT_GT(n, 10000);
  EXPECT_NEAR(sum / n, 0.0, 0.003);
  EXPECT_GE(low, -0.1 - 1e-6);
  EXPECT_LE(high, 0.1 + 1e-6);
  EXPECT_GT(high - low, 0.19);
}

TEST(SimulatorTest, PedestriansHideSomeWalls) {
  const World world = BuiltinWorld("empty-room");
  SimulationOptions options = Noiseless();
  const Dataset empty = Simulate(world, options);
  options.noise.pedestrians = 4;
  const Dataset crowded = Simulate(world, options);
  ASSERT_EQ(empty.scans.size(), crowded.scans.size());
  int shorter = 0;
  for (std::size_t i = 0; i < empty.scans.size(); ++i) {
    for (std::size_t b = 0; b < empty.scans[i].size(); ++b) {
      ASSERT_LE(crowded.scans[i].ranges[b], empty.scans[i].ranges[b]);
      shorter += crowded.scans[i].ranges[b] < empty.scans[i].ranges[b];
    }
  }
  EXPECT_GT(shorter, 100);
}

TEST(SimulatorTest, OdometryDriftGrowsWithDistance) {
  const World world = BuiltinWorld("office-boxes");
  double early = 0.0;
  double late = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SimulationOptions options;
    options.seed = seed;
    const Dataset d = Simulate(world, options);
    const auto error = [&](std::size_t i) {
      return (d.scans[i].odometry.translation() - d.scans[i].true_pose->translation()).norm();
    };
    early += error(d.scans.size() / 10);
    late += error(d.scans.size() - 1);
  }
  EXPECT_GT(late, 3.0 * early);
  EXPECT_GT(late / 5, 0.1);  // more than 10 cm after 30 m
}

TEST(SimulatorTest, RejectsBadOptions) {
  const World world = BuiltinWorld("empty-room");
  SimulationOptions options;
  options.scan_interval = 0.0;
  EXPECT_THROW(Simulate(world, options), Error);
  options = {};
  options.laser.beams = 0;
  EXPECT_THROW(Simulate(world, options), Error);
  options = {};
  options.step = -1.0;
  EXPECT_THROW(Simulate(world, options), Error);
}

TEST(WriteSimulationTest, WritesLogMapAndTruthReproducibly) {
  const World world = BuiltinWorld("s-corridor");
  SimulationOptions options;
  options.noise.gaussian_sigma = 0.02;
  options.max_scans = 25;
  const Dataset d = Simulate(world, options);
  const TempDir scratch;
  const std::filesystem::path dir = scratch / "out" / "nested";
  WriteSimulation(d, world, dir);

  const std::string truth = ReadAll(dir / "truth.txt");
  std::istringstream lines(truth);
  std::string line;
  std::size_t count = 0;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    double t, x, y, theta;
    ASSERT_TRUE(fields >> t >> x >> y >> theta) << line;
    EXPECT_NEAR(t, d.scans[count].timestamp, 1e-6);
    EXPECT_NEAR(x, d.scans[count].true_pose->x(), 1e-6);
    EXPECT_NEAR(theta, d.scans[count].true_pose->theta(), 1e-6);
    ++count;
  }
  EXPECT_EQ(count, d.scans.size());
  EXPECT_THAT(truth.substr(0, 18), HasSubstr("1000000000.000000 "));

  EXPECT_EQ(ReadLineMap(dir / "world.lines").size(), world.map.size());

  const Dataset back = ReadCarmen(dir / "log.clf");
  ASSERT_EQ(back.scans.size(), d.scans.size());
  EXPECT_TRUE(back.has_ground_truth());
  EXPECT_EQ(back.scans[3].ranges, d.scans[3].ranges);
  EXPECT_EQ(back.scans[3].range_max, 8.0);
  EXPECT_THAT(ReadAll(dir / "log.clf"), HasSubstr("FLASER 361 "));

  // Same seed, same bytes.
  const std::filesystem::path again = scratch / "again";
  WriteSimulation(Simulate(world, options), world, again);
  for (const char* file : {"log.clf", "world.lines", "truth.txt"}) {
    EXPECT_EQ(ReadAll(dir / file), ReadAll(again / file)) << file;
  }
}

TEST(WriteSimulationTest, UncreatableDirectoryNamesThePath) {
  const TempDir scratch;
  const std::filesystem::path file = scratch / "file";
  std::ofstream(file) << "x";
  const World world = BuiltinWorld("empty-room");
  SimulationOptions options;
  options.max_scans = 2;
  try {
    WriteSimulation(Simulate(world, options), world, file / "sub");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr((file / "sub").string()));
  }
}

}  // namespace
}  // namespace evoslam
