#include "common/slam/immune/immune_slam.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <string>
#include <vector>

#include "common/eval/trajectory_errors.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// 004's experiment in small: an office with boxes (convex corners) and a route of about 30 m,
// odometry whose heading drifts, a laser cut at 3 m by the method.
const Dataset& Lab() {
  static const Dataset lab = [] {
    SimulationOptions o;
    o.laser.beams = 181;
    o.noise.gaussian_sigma = 0.01;
    o.noise.odometry.rotation_bias = 0.03;
    o.step = 0.1;
    o.seed = 7;
    return Simulate(BuiltinWorld("office-boxes"), o);
  }();
  return lab;
}

std::vector<Pose2> Odometry(const Dataset& dataset) {
  std::vector<Pose2> poses;
  for (const LaserScan& scan : dataset.scans) poses.push_back(scan.pose);
  return poses;
}

// A search small enough for a unit test: windows of 8 segments, 20 candidates, 30 generations.
proto::ImmuneParams Quick() {
  proto::ImmuneParams p;
  p.mutable_search()->set_population(20);
  p.mutable_search()->set_generations(30);
  p.mutable_search()->set_window_segments(8);
  p.mutable_evidence()->set_beam_stride(3);
  p.set_scan_stride(2);
  return p;
}

std::vector<StampedPose> Stamped(const Dataset& dataset, std::span<const Pose2> poses) {
  std::vector<StampedPose> out;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    out.push_back({dataset.scans[k].timestamp, poses[k]});
  }
  return out;
}

std::vector<StampedPose> Truth(const Dataset& dataset) {
  std::vector<StampedPose> out;
  for (const LaserScan& scan : dataset.scans) out.push_back({scan.timestamp, *scan.true_pose});
  return out;
}

TEST(ImmuneSlamTest, ItMakesTheMapMoreConsistentAndTheTrajectoryCloserToTheTruth) {
  const Dataset& lab = Lab();
  const std::vector<Pose2> odometry = Odometry(lab);
  const ImmuneSlamResult r = RunImmuneSlam(lab, odometry, Quick(), 1, {});
  ASSERT_EQ(r.poses.size(), odometry.size());
  ASSERT_EQ(r.report.objectives_size(), 3);
  EXPECT_LT(r.report.objectives(0), r.report.start_objectives(0));
  EXPECT_GT(r.report.windows_size(), 1);
  EXPECT_GT(r.evaluations, 0u);
  const double before = ComputeAbsoluteErrors(Stamped(lab, odometry), Truth(lab)).rms_translation;
  const double after = ComputeAbsoluteErrors(Stamped(lab, r.poses), Truth(lab)).rms_translation;
  EXPECT_LT(after, before);
  // The member applied is no worse than the window as it stood by the weighted sum that chose it.
  const proto::ImmuneParams quick = Quick();
  const proto::ImmuneSearchParams& s = quick.search();
  const auto sum = [&](const auto& f) {
    return f.Get(0) + s.occupied_weight() * f.Get(1) + s.empty_weight() * f.Get(2);
  };
  for (const proto::ImmuneWindowRecord& w : r.report.windows()) {
    ASSERT_EQ(w.chosen_objectives_size(), 3);
    if (w.applied()) {
      EXPECT_LE(sum(w.chosen_objectives()), sum(w.start_objectives()));
    }
    EXPECT_EQ(w.front_size() % 3, 0);
    EXPECT_LT(w.chosen(), static_cast<std::uint32_t>(w.front_size() / 3));
  }
}

TEST(ImmuneSlamTest, TheResultIsAFunctionOfTheSeedWhateverTheThreads) {
  const Dataset& lab = Lab();
  const std::vector<Pose2> odometry = Odometry(lab);
  proto::ImmuneParams p = Quick();
  p.mutable_search()->set_generations(6);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const ImmuneSlamResult one = RunImmuneSlam(lab, odometry, p, 3, {});
  omp_set_num_threads(2);
  const ImmuneSlamResult two = RunImmuneSlam(lab, odometry, p, 3, {});
  omp_set_num_threads(threads);
  EXPECT_EQ(one.poses, two.poses);
  EXPECT_EQ(one.evaluations, two.evaluations);
  const ImmuneSlamResult other = RunImmuneSlam(lab, odometry, p, 4, {});
  EXPECT_NE(one.poses, other.poses);
}

TEST(ImmuneSlamTest, AResumedRunEndsAsTheUninterruptedOne) {
  const Dataset& lab = Lab();
  const std::vector<Pose2> odometry = Odometry(lab);
  proto::ImmuneParams p = Quick();
  p.mutable_search()->set_generations(6);
  std::vector<proto::ImmuneCheckpoint> checkpoints;
  ImmuneSlamRuntime record;
  record.checkpoint = [&](const proto::ImmuneCheckpoint& c) { checkpoints.push_back(c); };
  const ImmuneSlamResult whole = RunImmuneSlam(lab, odometry, p, 5, record);
  ASSERT_GE(checkpoints.size(), 2u);
  ImmuneSlamRuntime resume;
  resume.resume = &checkpoints[checkpoints.size() / 2];
  const ImmuneSlamResult resumed = RunImmuneSlam(lab, odometry, p, 5, resume);
  EXPECT_EQ(resumed.poses, whole.poses);
  EXPECT_EQ(resumed.evaluations, whole.evaluations);
  EXPECT_EQ(resumed.report.windows_size(), whole.report.windows_size());
  EXPECT_EQ(resumed.map.objectives(), whole.map.objectives());
}

TEST(ImmuneSlamTest, ProgressAdvancesToTheEnd) {
  const Dataset& lab = Lab();
  const std::vector<Pose2> odometry = Odometry(lab);
  proto::ImmuneParams p = Quick();
  p.mutable_search()->set_generations(3);
  std::vector<SlamProgress> seen;
  ImmuneSlamRuntime runtime;
  runtime.progress = [&](const SlamProgress& progress) { seen.push_back(progress); };
  RunImmuneSlam(lab, odometry, p, 1, runtime);
  ASSERT_FALSE(seen.empty());
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i].done, seen[i - 1].done);
  EXPECT_EQ(seen.back().done, odometry.size());
  EXPECT_EQ(seen.back().total, odometry.size());
}

TEST(ImmuneSlamTest, DuckettsVariantSearchesOneObjective) {
  const Dataset& lab = Lab();
  const std::vector<Pose2> odometry = Odometry(lab);
  proto::ImmuneParams p = Quick();
  p.set_variant("duckett");
  p.mutable_search()->set_generations(4);
  const ImmuneSlamResult r = RunImmuneSlam(lab, odometry, p, 1, {});
  for (const proto::ImmuneWindowRecord& w : r.report.windows()) {
    EXPECT_EQ(w.start_objectives_size(), 1);
    EXPECT_LE(w.chosen_objectives(0), w.start_objectives(0));
    EXPECT_TRUE(w.applied());  // one objective: the elitist search keeps the start or better
  }
}

TEST(ImmuneSlamTest, ALogTooShortForOneSegmentIsRefused) {
  Dataset shortened = Lab();
  shortened.scans.resize(4);  // 0.3 m of travel
  const std::vector<Pose2> odometry = Odometry(shortened);
  try {
    RunImmuneSlam(shortened, odometry, Quick(), 1, {});
    FAIL() << "a log of 0.3 m was optimised";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("less than one segment"), std::string::npos) << e.what();
  }
}

TEST(ImmuneSlamTest, ParametersOutOfRangeAreRefusedByName) {
  proto::ImmuneParams p = Quick();
  p.set_variant("nsga");
  EXPECT_THROW(ValidateImmuneParams(p), Error);
  p = Quick();
  p.mutable_search()->set_p_immunity(1.5);
  try {
    ValidateImmuneParams(p);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("p_immunity"), std::string::npos) << e.what();
  }
  p = Quick();
  p.set_scan_stride(0);
  EXPECT_THROW(ValidateImmuneParams(p), Error);
  EXPECT_NO_THROW(ValidateImmuneParams(Quick()));
}

}  // namespace
}  // namespace evoslam
