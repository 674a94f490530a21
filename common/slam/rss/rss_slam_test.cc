#include "common/slam/rss/rss_slam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/rss/rss_proto.h"
#include "common/slam/slam_params.h"
#include "common/slam/slam_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

Dataset Drive(std::size_t scans) {
  SimulationOptions sim;
  sim.laser.beams = 91;
  sim.noise.odometry.rotation_bias = 0.02;
  sim.max_scans = scans;
  return Simulate(BuiltinWorld("office-boxes"), sim);
}

// Small searches, so that a run takes a fraction of a second.
RssSlamParams Quick() {
  RssSlamParams p;
  p.mutable_local()->set_iterations(10);
  p.mutable_global()->set_every_scans(25);
  p.mutable_global()->set_generations(4);
  p.mutable_global()->set_partitions(3);
  return p;
}

void ExpectSameRun(const RssSlamResult& a, const RssSlamResult& b) {
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_EQ(a.trajectory[i].pose.x(), b.trajectory[i].pose.x()) << "scan " << i;
    EXPECT_EQ(a.trajectory[i].pose.y(), b.trajectory[i].pose.y()) << "scan " << i;
    EXPECT_EQ(a.trajectory[i].pose.theta(), b.trajectory[i].pose.theta()) << "scan " << i;
  }
  EXPECT_EQ(a.local_evaluations, b.local_evaluations);
  EXPECT_EQ(a.global_evaluations, b.global_evaluations);
  ASSERT_EQ(a.global_searches.size(), b.global_searches.size());
  for (std::size_t g = 0; g < a.global_searches.size(); ++g) {
    EXPECT_EQ(a.global_searches[g].applied, b.global_searches[g].applied);
    EXPECT_EQ(a.global_searches[g].after[0], b.global_searches[g].after[0]);
  }
  EXPECT_EQ(a.map.total(), b.map.total());
  EXPECT_EQ(a.map.occupied(), b.map.occupied());
}

TEST(RssSlamTest, LocalOnlyIsTheLocalSearch) {
  const Dataset d = Drive(60);
  RssSlamParams params = Quick();
  params.mutable_global()->set_enabled(false);
  std::vector<Pose2> last;
  // Both ways of scoring a step: every return, and only those within the previous scan's reach
  // less a margin (6 m of the 8 m laser's, which must change the trajectory).
  for (const double margin : {-1.0, 6.0}) {
    params.mutable_local()->set_reach_margin_m(margin);
    const RssSlamResult slam = testing::RunRss(d, params, 5);
    HitCountGrid map = EmptyMapFor(d, params.map(), params.local());
    const LocalSearchResult local = RunLocalSearch(d, params.local(), 5, map);
    ASSERT_EQ(slam.trajectory.size(), local.trajectory.size());
    for (std::size_t i = 0; i < local.trajectory.size(); ++i) {
      EXPECT_EQ(slam.trajectory[i].pose.translation(), local.trajectory[i].pose.translation());
      EXPECT_EQ(slam.trajectory[i].timestamp, d.scans[i].timestamp);
    }
    EXPECT_EQ(slam.local_evaluations, local.evaluations);
    EXPECT_TRUE(slam.global_searches.empty());
    EXPECT_EQ(slam.map.total(), map.total());
    last.push_back(slam.trajectory.back().pose);
  }
  EXPECT_NE(last[0].translation(), last[1].translation()) << "the margin changed nothing";
}

TEST(RssSlamTest, GlobalSearchesRunEveryKStepsOverTheStepsSinceTheLast) {
  const Dataset d = Drive(80);
  const RssSlamParams params = Quick();
  const RssSlamResult r = testing::RunRss(d, params, 5);
  std::size_t periodic = 0, next_first = 0;
  for (const GlobalSearchRecord& g : r.global_searches) {
    if (g.loop) continue;
    ++periodic;
    EXPECT_EQ(g.first, next_first);
    EXPECT_EQ(g.last - g.first, params.global().every_scans());
    next_first = g.last;
    EXPECT_GT(g.evaluations, 0u);
    // Applied exactly when the correction sharpens the map by the minimum gain or frees the path.
    EXPECT_EQ(g.applied, g.after[0] < g.before[0] - params.global().min_periodic_sharpening() *
                                                        std::abs(g.before[0]) ||
                             g.after[1] < g.before[1]);
  }
  EXPECT_EQ(periodic, 80 / params.global().every_scans());
  EXPECT_EQ(r.global_evaluations, [&] {
    std::size_t n = 0;
    for (const GlobalSearchRecord& g : r.global_searches) n += g.evaluations;
    return n;
  }());
}

TEST(RssSlamTest, ProblemsRebuiltFromTheWireGiveTheSameRun) {
  const Dataset d = Drive(60);
  const RssSlamParams params = Quick();
  const RssSlamResult here = testing::RunRss(d, params, 9);

  // What a worker does: the task through its wire form, the base map and problem rebuilt.
  struct Rebuilt {
    std::vector<Pose2> poses;
    std::optional<HitCountGrid> base;
    std::optional<GlobalSearchProblem> problem;
  };
  std::vector<std::shared_ptr<Rebuilt>> built;
  RssSlamRuntime runtime;
  runtime.global = [&](const GlobalSearchTask& task, const GlobalSearchProblem&) {
    auto r = std::make_shared<Rebuilt>();
    const GlobalSearchTask copy = GlobalSearchTaskFromProto(ToProto(task), r->poses);
    r->base.emplace(BaseMapFor(d, r->poses, copy.first, copy.last, params));
    r->problem.emplace(MakeGlobalSearchProblem(d, copy, params.global(), *r->base));
    built.push_back(r);
    return LocalIslandStepper(*r->problem, 1);
  };
  const RssSlamResult remote = testing::RunRss(d, params, 9, runtime);
  EXPECT_EQ(built.size(), here.global_searches.size());
  ExpectSameRun(here, remote);
}

// Resumed from any of a run's checkpoints, between scans or part-way through a search, the run
// ends as the uninterrupted one does; a state that does not fit the log is refused.
void ExpectResumesGiveTheUninterruptedRun(bool free_frontier) {
  const Dataset d = Drive(60);
  RssSlamParams params = Quick();
  params.mutable_local()->set_free_frontier(free_frontier);
  params.mutable_global()->set_generations(
      25);  // three epochs of 10: checkpoints inside each search...
  params.mutable_global()->set_preset(
      "immune-004");  // ...which 002's (mu+lambda) ends early here, converged
  std::vector<RssSlamState> states, part_way;
  RssSlamRuntime record;
  record.checkpoint = [&](const RssSlamState& s) {
    if (s.search) {
      part_way.push_back(s);
    } else if (s.next_scan == 26 || s.next_scan == 40) {
      states.push_back(s);
    }
  };
  const RssSlamResult whole = testing::RunRss(d, params, 3, record);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].global_searches.size(), 1u);  // just after the first global search
  // Two searches, each checkpointed after its first two epochs.
  ASSERT_EQ(part_way.size(), 4u);
  EXPECT_EQ(part_way[0].next_scan, 25u);  // the 25th scan started it
  EXPECT_TRUE(part_way[0].global_searches.empty());
  EXPECT_EQ(part_way[1].search->epoch, part_way[0].search->epoch + 1);
  states.insert(states.end(), part_way.begin(), part_way.end());
  for (const RssSlamState& state : states) {
    RssSlamRuntime resume;
    resume.resume = &state;
    ExpectSameRun(whole, testing::RunRss(d, params, 3, resume));
  }
  RssSlamState broken = states[0];
  broken.poses.pop_back();
  RssSlamRuntime bad;
  bad.resume = &broken;
  EXPECT_THROW(testing::RunRss(d, params, 3, bad), Error);
  // A part-way search said to be a loop's, with no loop at its scan.
  broken = part_way[0];
  broken.search_on_loop = true;
  EXPECT_THROW(testing::RunRss(d, params, 3, bad), Error);
}

// Also with the seen space's edge left free, whose ray coverage a resumed run renders afresh.
TEST(RssSlamTest, ResumingFromAnyCheckpointGivesTheUninterruptedRun) {
  for (const bool free_frontier : {false, true}) {
    SCOPED_TRACE(free_frontier ? "edge free" : "edge counted");
    ExpectResumesGiveTheUninterruptedRun(free_frontier);
  }
}

// The run reports scans done of all, never going back, with each global search as the step
// under way at the scans before the one that started it; reporting changes nothing, and a run
// resumed from a checkpoint carries on from where the progress stood.
TEST(RssSlamTest, ProgressIsScansDoneWithTheGlobalSearchAsItsStep) {
  const Dataset d = Drive(60);
  RssSlamParams params = Quick();
  params.mutable_global()->set_generations(25);  // epochs of 10: 10, 20 and 25 generations
  params.mutable_global()->set_preset("immune-004");
  std::vector<SlamProgress> seen;
  // The number of reports seen when each checkpoint part-way through a search was offered.
  std::vector<std::pair<RssSlamState, std::size_t>> part_way;
  RssSlamRuntime runtime;
  runtime.progress = [&](const SlamProgress& p) { seen.push_back(p); };
  runtime.checkpoint = [&](const RssSlamState& s) {
    if (s.search) part_way.emplace_back(s, seen.size());
  };
  const RssSlamResult run = testing::RunRss(d, params, 3, runtime);
  ExpectSameRun(testing::RunRss(d, params, 3), run);

  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.front().done, 0u);
  EXPECT_EQ(seen.back().done, 60u);
  EXPECT_TRUE(seen.back().step.empty());
  std::vector<std::size_t> searches_at;  // the scans done when each search started
  for (std::size_t k = 0; k < seen.size(); ++k) {
    const SlamProgress& p = seen[k];
    SCOPED_TRACE("report " + std::to_string(k));
    EXPECT_EQ(p.total, 60u);
    if (k > 0) {
      EXPECT_GE(p.done, seen[k - 1].done);
      EXPECT_GE(p.evaluations, seen[k - 1].evaluations);
    }
    if (p.step.empty()) continue;
    EXPECT_EQ(p.step, "global search");
    EXPECT_EQ(p.step_total, 25u);
    EXPECT_LE(p.step_done, p.step_total);
    if (p.step_done == 0) {
      searches_at.push_back(p.done);
    } else {
      ASSERT_GT(k, 0u);
      EXPECT_EQ(p.done, seen[k - 1].done) << "the scans stand still during a search";
      EXPECT_GT(p.step_done, seen[k - 1].step_done);
    }
  }
  ASSERT_EQ(searches_at.size(), run.global_searches.size());
  ASSERT_EQ(searches_at.size(), 2u);
  for (std::size_t g = 0; g < searches_at.size(); ++g) {
    EXPECT_EQ(searches_at[g], run.global_searches[g].last - 1) << "search " << g;
  }

  ASSERT_FALSE(part_way.empty());
  for (const auto& [state, reports] : part_way) {
    std::vector<SlamProgress> resumed;
    RssSlamRuntime resume;
    resume.resume = &state;
    resume.progress = [&](const SlamProgress& p) { resumed.push_back(p); };
    ExpectSameRun(run, testing::RunRss(d, params, 3, resume));
    ASSERT_FALSE(resumed.empty());
    EXPECT_GE(resumed.front().done, seen[reports - 1].done) << "went back on resuming";
    EXPECT_EQ(resumed.front().done, state.next_scan - 1);
    EXPECT_EQ(resumed.back().done, 60u);
  }
}

TEST(RssSlamTest, SeedsChangeTheRun) {
  const Dataset d = Drive(40);
  const RssSlamParams params = Quick();
  const RssSlamResult a = testing::RunRss(d, params, 1), b = testing::RunRss(d, params, 2);
  EXPECT_NE(a.trajectory.back().pose.x(), b.trajectory.back().pose.x());
}

TEST(RssSlamTest, PeriodicBoundsAreTheRefinementsAndLoopBoundsFollowTheDiscrepancy) {
  const GlobalSearchParams params;
  const std::vector<Pose2> poses = {Pose2(0, 0, 0), Pose2(1, 0, 0), Pose2(2, 0.3, 0.05)};
  EXPECT_EQ(GlobalSearchBounds(params, poses, std::nullopt), RefineBounds(params));
  // The loop says scan 2 stands where scan 0 does: 2.02 m and 0.05 rad away.
  const LoopConstraint loop{0, 2, Pose2()};
  const Eigen::Vector3d b = GlobalSearchBounds(params, poses, loop);
  EXPECT_EQ(b.x(), params.max_error_x_m());  // capped
  EXPECT_NEAR(b.z(), 1.5 * 0.05 + params.refine_bound_theta_rad(), 1e-12);
}

TEST(RssSlamTest, RefusesBadParametersAndEmptyLogs) {
  RssSlamParams params;
  params.mutable_global()->set_generations(0);
  EXPECT_THROW(ValidateRssSlamParams(params), Error);
  params = {};
  params.mutable_global()->set_preset("no-such-preset");
  EXPECT_THROW(ValidateRssSlamParams(params), Error);
  params = {};
  params.mutable_global()->set_refine_bound_x_m(-1.0);
  EXPECT_THROW(ValidateRssSlamParams(params), Error);
  Dataset empty;
  empty.source = "empty.clf";
  EXPECT_THROW(testing::RunRss(empty, {}, 1), Error);
}

// A corrupt odometry reading is refused before any work, naming the scan it is in.
TEST(RssSlamTest, RefusesALogWhoseOdometryJumpsBeyondTheLasersReach) {
  SimulationOptions sim;
  sim.max_scans = 30;
  Dataset d = Simulate(BuiltinWorld("s-corridor"), sim);
  d.source = "jump.clf";
  d.scans[20].odometry = Pose2(3000.0, 0.0, 0.0);
  try {
    testing::RunRss(d, {}, 1);
    ADD_FAILURE() << "a 3 km odometry jump was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("jump.clf: odometry moves"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("from scan 19 to scan 20"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace evoslam
