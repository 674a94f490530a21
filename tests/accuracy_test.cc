// Accuracy on data with known ground truth: the L1/L2 comparative study's environments A and B,
// simulated, and the real Intel and ACES logs' relations.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <tuple>

#include "common/eval/trajectory_errors.h"
#include "common/io/carmen_reader.h"
#include "common/io/relations.h"
#include "common/localization/localizer.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/transform/angle_units.h"

namespace evoslam {
namespace {

struct StudyRun {
  std::size_t scans = 0;
  AbsoluteErrors errors;
};

// DE/rand/1/exp on F3, POP 25, GEN 25, 60 x 60 cm window: the study's settings, unless another
// optimizer is named.
StudyRun LocalizeInWorld(const std::string& world_name, double bandwidth, std::uint64_t seed,
                         const std::string& optimizer = "de", int pedestrians = 0,
                         double f3_cap = 0.0) {
  const World world = BuiltinWorld(world_name);
  SimulationOptions sim;
  sim.noise.uniform_bandwidth = bandwidth;
  sim.noise.pedestrians = pedestrians;
  sim.seed = seed;
  const Dataset log = Simulate(world, sim);
  LocalizeOptions options;
  options.seed = seed;
  options.estimator.optimizer = ParseOptimizer(optimizer, options.estimator.algorithm);
  options.estimator.fitness.f3_cap = f3_cap;
  const LocalizeResult result = Localize(MapModel(world.map), log, options);
  std::vector<StampedPose> truth;
  for (const LaserScan& s : log.scans) truth.push_back({s.timestamp, *s.true_pose});
  return {log.scans.size(), ComputeAbsoluteErrors(result.trajectory, truth)};
}

class StudyEnvironmentTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StudyEnvironmentTest, CentimetreAccuracyAt20cmNoise) {
  const StudyRun run = LocalizeInWorld(GetParam(), 0.20, 1);
  EXPECT_GE(run.scans, 200u);
  EXPECT_EQ(run.errors.poses, run.scans);
  EXPECT_LE(run.errors.rms_x, 0.02);
  EXPECT_LE(run.errors.rms_y, 0.02);
  EXPECT_LE(run.errors.rms_theta, 0.5 * kDegree);
  RecordProperty("rms_x_cm", std::to_string(100 * run.errors.rms_x));
  RecordProperty("rms_y_cm", std::to_string(100 * run.errors.rms_y));
  RecordProperty("rms_theta_deg", std::to_string(run.errors.rms_theta / kDegree));
}

TEST_P(StudyEnvironmentTest, KeepsTrackAt300cmNoise) {
  const StudyRun run = LocalizeInWorld(GetParam(), 3.0, 2);
  // RMS per axis, as eq. 9 of 003 and the 20 cm criterion above. Over seeds 2 to 7 the corridor,
  // whose long straight legs say little about the position along them, gives 9.8 to 12.1 cm
  // per axis; the room with objects 3.4 to 5.2 cm. A lost track would be off by metres.
  EXPECT_LE(run.errors.rms_x, 0.15);
  EXPECT_LE(run.errors.rms_y, 0.15);
  EXPECT_LE(run.errors.max_translation, 0.6);
}

// Environment A: the s-shaped corridor; B: the room with many static objects.
INSTANTIATE_TEST_SUITE_P(EnvironmentsAB, StudyEnvironmentTest,
                         ::testing::Values("s-corridor", "static-objects"), [](const auto& info) {
                           std::string name = info.param;
                           std::erase(name, '-');
                           return name;
                         });

// Every engine optimizer meets the study's accuracy at 20 cm noise; the GAs, whose binary
// chromosomes live on the 1 cm search grid, at 003's looser figures for them.
using OptimizerCase = std::tuple<std::string, std::string>;
class StudyOptimizerTest : public ::testing::TestWithParam<OptimizerCase> {};

TEST_P(StudyOptimizerTest, AccurateAt20cmNoise) {
  const auto& [world, optimizer] = GetParam();
  const StudyRun run = LocalizeInWorld(world, 0.20, 1, optimizer);
  const bool ga = optimizer == "sga" || optimizer == "aga";
  const double position = ga ? 0.04 : 0.02;
  const double heading = (ga ? 1.0 : 0.5) * kDegree;
  EXPECT_EQ(run.errors.poses, run.scans);
  EXPECT_LE(run.errors.rms_x, position);
  EXPECT_LE(run.errors.rms_y, position);
  EXPECT_LE(run.errors.rms_theta, heading);
  RecordProperty("rms_x_cm", std::to_string(100 * run.errors.rms_x));
  RecordProperty("rms_y_cm", std::to_string(100 * run.errors.rms_y));
  RecordProperty("rms_theta_deg", std::to_string(run.errors.rms_theta / kDegree));
}

INSTANTIATE_TEST_SUITE_P(EnvironmentsAB, StudyOptimizerTest,
                         ::testing::Combine(::testing::Values("s-corridor", "static-objects"),
                                            ::testing::Values("pso", "sga", "aga", "island")),
                         [](const auto& info) {
                           std::string name =
                               std::get<0>(info.param) + "_" + std::get<1>(info.param);
                           std::erase(name, '-');
                           return name;
                         });

// People walking about, whom the map does not hold, shorten a few beams by metres. Each such beam
// can outweigh the rest of the scan in the papers' uncapped F3, which loses the robot on every
// seed tried (`evoslam simulate --world office-boxes --pedestrians 10 --noise-uniform 0.1 --seed
// N`, N = 1 to 4: 2.3 to 4.2 m aligned RMS); with each beam's term capped at 0.5 m the estimate
// stays within a few centimetres (seeds 1 to 3 here: 0.6 to 2.0 cm RMS per axis).
class PeopleTheMapLacksTest : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(PeopleTheMapLacksTest, CappedF3FollowsTheRobot) {
  const StudyRun capped = LocalizeInWorld("office-boxes", 0.10, GetParam(), "de", 10, 0.5);
  EXPECT_EQ(capped.errors.poses, capped.scans);
  EXPECT_LE(capped.errors.rms_x, 0.04);
  EXPECT_LE(capped.errors.rms_y, 0.04);
  EXPECT_LE(capped.errors.max_translation, 0.4);
  RecordProperty("rms_x_cm", std::to_string(100 * capped.errors.rms_x));
  RecordProperty("rms_y_cm", std::to_string(100 * capped.errors.rms_y));
}

INSTANTIATE_TEST_SUITE_P(Seeds, PeopleTheMapLacksTest, ::testing::Values(1u, 2u, 3u));

TEST(PapersF3AmongPeopleTest, LosesTheRobot) {
  const StudyRun uncapped = LocalizeInWorld("office-boxes", 0.10, 1, "de", 10);
  EXPECT_GT(uncapped.errors.rms_translation, 0.5);
}

// The relation metric on raw odometry reproduces the figures published with the data.
struct OdometryCase {
  const char* name;
  const char* log;
  const char* relations;
  double mean;
  double std;
};

class OdometryRelationTest : public ::testing::TestWithParam<OdometryCase> {};

TEST_P(OdometryRelationTest, MatchesPublishedOdometryError) {
  const OdometryCase& c = GetParam();
  const std::filesystem::path dir(EVOSLAM_DATA_DIR);
  if (!std::filesystem::exists(dir / c.log) || !std::filesystem::exists(dir / c.relations)) {
    GTEST_SKIP() << "real data absent from " << dir;
  }
  const Dataset log = ReadCarmen(dir / c.log);
  std::vector<StampedPose> odometry;
  for (const LaserScan& s : log.scans) odometry.push_back({s.timestamp, s.odometry});
  const auto relations = ReadRelations(dir / c.relations);
  const RelationErrors e = ComputeRelationErrors(odometry, relations);
  EXPECT_EQ(e.skipped, 0u);
  EXPECT_EQ(e.relations, relations.size());
  EXPECT_NEAR(e.translation_mean, c.mean, 0.01);
  EXPECT_NEAR(e.translation_std, c.std, 0.01);
}

INSTANTIATE_TEST_SUITE_P(
    IntelAndAces, OdometryRelationTest,
    ::testing::Values(OdometryCase{"intel", "intel.clf.bz2", "intel.relations", 7.37, 14.46},
                      OdometryCase{"aces", "aces.clf.bz2", "aces.relations", 0.56, 2.72}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace evoslam
