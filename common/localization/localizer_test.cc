#include "common/localization/localizer.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "common/engine/engine_proto.h"
#include "common/localization/localize_params.h"
#include "common/localization/test_scenes.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

LocalizeOptions IslandOptions() {
  LocalizeOptions options;
  options.seed = 21;
  options.estimator.optimizer = ParseOptimizer("island", options.estimator.algorithm);
  options.estimator.islands = 3;
  options.estimator.migration.interval = 5;
  return options;
}

void ExpectSameTrajectory(const LocalizeResult& a, const LocalizeResult& b) {
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_EQ(a.trajectory[i].pose, b.trajectory[i].pose) << i;
    EXPECT_EQ(a.fitness[i], b.fitness[i]) << i;
  }
  EXPECT_EQ(a.evaluations, b.evaluations);
}

TEST(LocalizeResumeTest, ResumingFromAnyCheckpointGivesTheUninterruptedResult) {
  const MapModel map(testing::BoxRoom());
  const Dataset d = testing::WalkThroughBoxRoom(6);
  const LocalizeOptions options = IslandOptions();
  std::vector<LocalizeState> states;
  LocalizeRuntime recording;
  recording.checkpoint = [&](const LocalizeState& s) { states.push_back(s); };
  const LocalizeResult straight = Localize(map, d, options, recording);
  // Between scans, and part-way through a scan's island search (25 generations in epochs of 5).
  ASSERT_GT(states.size(), 12u);
  std::size_t part_way = 0;
  for (const LocalizeState& s : states) part_way += s.search.has_value();
  EXPECT_EQ(part_way, 6u * 4u);
  for (const std::size_t k :
       {std::size_t{0}, std::size_t{3}, states.size() / 2, states.size() - 2}) {
    LocalizeRuntime resumed;
    resumed.resume = &states[k];
    ExpectSameTrajectory(Localize(map, d, options, resumed), straight);
  }
  LocalizeState wrong = states[3];
  wrong.next_scan = 5;
  LocalizeRuntime bad;
  bad.resume = &wrong;
  EXPECT_THROW(Localize(map, d, options, bad), Error);
}

// The service's way of running a search: islands shipped out and back as checkpoints, lattice
// batches evaluated in small chunks elsewhere. The result is the one computed in place.
TEST(LocalizeRuntimeTest, SearchesRunElsewhereGiveTheSameBits) {
  const MapModel map(testing::BoxRoom());
  const Dataset d = testing::WalkThroughBoxRoom(4);
  LocalizeRuntime remote;
  std::size_t shipped = 0, chunks = 0;
  remote.search = [&](std::size_t scan, const Pose2& center) {
    SearchRuntime runtime;
    runtime.step = [&, scan, center](const Problem&, std::vector<Island>& islands, bool start,
                                     std::size_t generations) {
      // The worker's side: the problem rebuilt from the job and the scan alone.
      const ScanProblem rebuilt = MakeScanProblem(map, d, scan, center, IslandOptions());
      for (Island& island : islands) {
        Island there = Island::FromCheckpoint(FromProto(ToProto(island.Checkpoint())));
        if (start) there.Start(*rebuilt.problem);
        if (generations > 0) there.Evolve(*rebuilt.problem, generations);
        island = Island::FromCheckpoint(FromProto(ToProto(there.Checkpoint())));
        ++shipped;
      }
    };
    runtime.evaluate = [&](const Problem& problem,
                           const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                           std::span<double> fitness) {
      for (Eigen::Index first = 0; first < candidates.cols(); first += 7, ++chunks) {
        const Eigen::Index n = std::min<Eigen::Index>(7, candidates.cols() - first);
        problem.Evaluate(
            candidates.middleCols(first, n),
            fitness.subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(n)));
      }
    };
    return runtime;
  };
  ExpectSameTrajectory(Localize(map, d, IslandOptions(), remote),
                       Localize(map, d, IslandOptions()));
  EXPECT_GT(shipped, 0u);

  LocalizeOptions exhaustive;
  exhaustive.estimator.optimizer = OptimizerKind::kExhaustive;
  exhaustive.estimator.exhaustive_step = 0.05;
  ExpectSameTrajectory(Localize(map, d, exhaustive, remote), Localize(map, d, exhaustive));
  EXPECT_GT(chunks, 4u * 10u);
}

// The odometry of a walk through the box room, exact, stalls over scans 3 to 6: they repeat scan
// 2's reading and scan 7's carries the five steps since. A window smaller than one step, centred
// on the odometry's step, follows the walk only once the stall is spread over the scans it held.
TEST(LocalizeTest, AnOdometryStallIsFilledInBeforeTheWindowsAreCentredOnIt) {
  const MapModel map(testing::BoxRoom());
  Dataset d = testing::WalkThroughBoxRoom(10);
  for (LaserScan& scan : d.scans) scan.odometry = *scan.true_pose;
  for (std::size_t i = 3; i <= 6; ++i) d.scans[i].odometry = d.scans[2].odometry;
  LocalizeOptions options;
  options.estimator.window = 0.04;  // smaller than the 5.8 cm step
  options.use_odometry = true;

  const LocalizeResult r = Localize(map, d, options);
  ASSERT_EQ(r.odometry_stalls.size(), 1u);
  EXPECT_EQ(r.odometry_stalls[0].first, 3u);
  EXPECT_EQ(r.odometry_stalls[0].last, 6u);
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    EXPECT_LT((r.trajectory[i].pose.translation() - d.scans[i].true_pose->translation()).norm(),
              0.01)
        << "scan " << i;
  }

  // The run held to its first scans leaves out the stall after them.
  options.max_scans = 3;
  EXPECT_TRUE(Localize(map, d, options).odometry_stalls.empty());

  // Windows centred on the previous estimate do not use odometry, so nothing is filled.
  options.max_scans = 0;
  options.use_odometry = false;
  EXPECT_TRUE(OdometryStallsOutsideTheWindow(d, options).empty());
}

TEST(LocalizeParamsTest, TheWireFormRunsTheSameJob) {
  const MapModel map(testing::BoxRoom());
  const Dataset d = testing::WalkThroughBoxRoom(3);
  for (const char* optimizer : {"de", "pso", "sga", "immune", "island", "exhaustive"}) {
    LocalizeOptions options = IslandOptions();
    options.estimator.optimizer = ParseOptimizer(optimizer, options.estimator.algorithm);
    options.estimator.heading_half_window = 0.3;
    options.estimator.heading_step = 0.01;
    options.estimator.exhaustive_step = 0.05;
    options.start = Pose2(2.5, 2.0, 0.55);
    options.max_range = 7.5;
    options.estimator.fitness = {.kind = FitnessKind::kF2, .f2_base = 0.03, .f2_slope = 0.02};
    proto::LocalizeParams wire;
    ASSERT_TRUE(wire.ParseFromString(ToProto(options).SerializeAsString()));
    const LocalizeOptions back = LocalizeOptionsFromProto(wire);
    EXPECT_EQ(back.estimator.heading_half_window, 0.3);
    EXPECT_EQ(back.start->x(), 2.5);
    EXPECT_EQ(back.estimator.fitness.f2_base, 0.03);
    EXPECT_EQ(back.estimator.fitness.f2_slope, 0.02);
    ExpectSameTrajectory(Localize(map, d, back), Localize(map, d, options));
  }
  LocalizeOptions capped = IslandOptions();
  capped.start = Pose2(2.5, 2.0, 0.55);
  capped.estimator.fitness = {.kind = FitnessKind::kF3, .f3_cap = 0.25};
  proto::LocalizeParams wire;
  ASSERT_TRUE(wire.ParseFromString(ToProto(capped).SerializeAsString()));
  const LocalizeOptions back = LocalizeOptionsFromProto(wire);
  EXPECT_EQ(back.estimator.fitness.f3_cap, 0.25);
  ExpectSameTrajectory(Localize(map, d, back), Localize(map, d, capped));
}

TEST(LocalizeParamsTest, RefusesParametersThatCannotWork) {
  proto::LocalizeParams p = ToProto(LocalizeOptions{});
  p.set_optimizer("simplex");
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.set_window_m(-1.0);
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.add_start(1.0);
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.clear_algorithm();
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.set_max_range_m(-2.0);
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.set_f2_base_m(-0.01);
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.set_f2_slope(std::numeric_limits<double>::infinity());
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
  p = ToProto(LocalizeOptions{});
  p.set_f3_cap_m(-0.3);
  EXPECT_THROW(LocalizeOptionsFromProto(p), Error);
}

// A job whose parameters predate F2's tolerance fields gets the papers' tolerance.
TEST(LocalizeParamsTest, AnUnsetF2ToleranceIsThePapers) {
  proto::LocalizeParams p = ToProto(LocalizeOptions{});
  p.clear_f2_base_m();
  p.clear_f2_slope();
  const LocalizeOptions back = LocalizeOptionsFromProto(p);
  EXPECT_EQ(back.estimator.fitness.f2_base, FitnessParams{}.f2_base);
  EXPECT_EQ(back.estimator.fitness.f2_slope, FitnessParams{}.f2_slope);
}

}  // namespace
}  // namespace evoslam
