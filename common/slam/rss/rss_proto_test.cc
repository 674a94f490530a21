#include "common/slam/rss/rss_proto.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "common/engine/archipelago.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Four scans done, a loop found at scan 3 and the global search it triggered, and an earlier
// periodic search; values chosen so that no digit survives a lossy conversion.
RssSlamState PartWay() {
  RssSlamState state;
  state.next_scan = 4;
  state.poses = {Pose2(0.1, -0.2, 3.0), Pose2(1.0 / 3, 2.0, -3.1), Pose2(2.0 / 7, 1e-9, 0.5),
                 Pose2(-4.25, 5.5, 1.0 / 9)};
  state.loops = {{{0, 3, Pose2(0.01, -0.02, 0.003)}, 0.875, 0.0625}};
  state.global_searches = {{.first = 0,
                            .last = 2,
                            .loop = std::nullopt,
                            .applied = false,
                            .evaluations = 500,
                            .seconds = 0.25,
                            .before = {-1.5, -0.5},
                            .after = {-1.25, -0.5}},
                           {.first = 1,
                            .last = 4,
                            .loop = state.loops[0],
                            .applied = true,
                            .evaluations = 700,
                            .seconds = 1.0 / 3,
                            .before = {-2.0, -1.0 / 7},
                            .after = {-2.5, -0.125}}};
  state.local_evaluations = 930;
  state.global_evaluations = 1200;
  state.last_global = 4;
  state.last_loop = 3;
  state.times = {.local = 0.5, .detection = 0.125, .global = 1.0 / 3, .total = 2.0};
  return state;
}

void ExpectSamePose(const Pose2& a, const Pose2& b) {
  EXPECT_EQ(a.x(), b.x());
  EXPECT_EQ(a.y(), b.y());
  EXPECT_EQ(a.theta(), b.theta());
}

void ExpectSameLoop(const LoopClosure& a, const LoopClosure& b) {
  EXPECT_EQ(a.constraint.earlier, b.constraint.earlier);
  EXPECT_EQ(a.constraint.later, b.constraint.later);
  ExpectSamePose(a.constraint.relative, b.constraint.relative);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.distinctness, b.distinctness);
}

TEST(RssCheckpointTest, RoundTripsEveryPoseLoopSearchAndCounter) {
  const RssSlamState state = PartWay();
  proto::RssCheckpoint wire;
  ASSERT_TRUE(wire.ParseFromString(ToProto(state).SerializeAsString()));
  const RssSlamState back = RssSlamStateFromProto(wire);

  EXPECT_EQ(back.next_scan, 4u);
  ASSERT_EQ(back.poses.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) ExpectSamePose(back.poses[i], state.poses[i]);
  ASSERT_EQ(back.loops.size(), 1u);
  ExpectSameLoop(back.loops[0], state.loops[0]);
  ASSERT_EQ(back.global_searches.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const GlobalSearchRecord &a = back.global_searches[i], &b = state.global_searches[i];
    EXPECT_EQ(a.first, b.first);
    EXPECT_EQ(a.last, b.last);
    EXPECT_EQ(a.applied, b.applied);
    EXPECT_EQ(a.evaluations, b.evaluations);
    EXPECT_EQ(a.seconds, b.seconds);
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(a.before[k], b.before[k]);
      EXPECT_EQ(a.after[k], b.after[k]);
    }
    ASSERT_EQ(a.loop.has_value(), b.loop.has_value()) << "search " << i;
    if (a.loop) ExpectSameLoop(*a.loop, *b.loop);
  }
  EXPECT_EQ(back.local_evaluations, 930u);
  EXPECT_EQ(back.global_evaluations, 1200u);
  EXPECT_EQ(back.last_global, 4u);
  EXPECT_EQ(back.last_loop, 3u);
  EXPECT_EQ(back.times.local, 0.5);
  EXPECT_EQ(back.times.detection, 0.125);
  EXPECT_EQ(back.times.global, 1.0 / 3);
  EXPECT_EQ(back.times.total, 2.0);
  EXPECT_FALSE(back.search.has_value());
}

// The loop's global search after its first epoch: its islands come back as they were.
TEST(RssCheckpointTest, ASearchPartWayRoundTrips) {
  RssSlamState state = PartWay();
  state.global_searches.pop_back();
  StopCriteria stop;
  stop.max_generations = 100;
  ArchipelagoCheckpoint islands =
      Archipelago(GlobalIslandModel(GlobalSearchParams{}), stop, 77).Checkpoint();
  islands.epoch = 1;
  state.search = islands;
  state.search_on_loop = true;
  const RssSlamState back = RssSlamStateFromProto(ToProto(state));
  ASSERT_TRUE(back.search.has_value());
  EXPECT_TRUE(back.search_on_loop);
  EXPECT_EQ(back.search->seed, 77u);
  EXPECT_EQ(back.search->epoch, 1u);
  EXPECT_EQ(back.search->islands.size(), islands.islands.size());
  EXPECT_EQ(back.search->stop.max_generations, 100u);
  EXPECT_EQ(back.global_searches.size(), 1u);
}

TEST(RssCheckpointTest, TheStartOfARunRoundTrips) {
  const RssSlamState back = RssSlamStateFromProto(ToProto(RssSlamState{}));
  EXPECT_EQ(back.next_scan, 0u);
  EXPECT_TRUE(back.poses.empty());
  EXPECT_TRUE(back.loops.empty());
  EXPECT_TRUE(back.global_searches.empty());
}

// PartWay() broken one way, and what the refusal must say.
struct Broken {
  std::function<void(proto::RssCheckpoint&)> change;
  std::string says;
};

void ExpectEachRefused(const std::vector<Broken>& cases) {
  for (const Broken& broken : cases) {
    proto::RssCheckpoint c = ToProto(PartWay());
    broken.change(c);
    try {
      RssSlamStateFromProto(c);
      ADD_FAILURE() << "accepted a checkpoint that should say '" << broken.says << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(broken.says), std::string::npos) << e.what();
    }
  }
}

TEST(RssCheckpointTest, RefusesPosesThatDoNotMatchTheScansDone) {
  ExpectEachRefused({
      {[](auto& c) { c.add_x(1.0); }, "5 x, 4 y and 4 theta values for the 4 scans done"},
      {[](auto& c) { c.set_next_scan(5); }, "4 x, 4 y and 4 theta values for the 5 scans done"},
  });
}

TEST(RssCheckpointTest, RefusesLoopsAndSearchesBeyondTheScansDone) {
  ExpectEachRefused({
      {[](auto& c) { c.mutable_loops(0)->set_later(4); }, "the loop from scan 4 back to 0"},
      {[](auto& c) { c.mutable_loops(0)->set_earlier(3); }, "the loop from scan 3 back to 3"},
      {[](auto& c) { c.mutable_loops(0)->mutable_relative()->RemoveLast(); },
       "with 2 relative values does not fit scans [0, 4)"},
      {[](auto& c) { c.mutable_global_searches(0)->set_last(5); },
       "a global search over scans [0, 5)"},
      {[](auto& c) { c.mutable_global_searches(0)->mutable_after()->Clear(); },
       "with 2 + 0 objectives"},
      {[](auto& c) { c.set_last_global(9); }, "the last global search at scan 9"},
  });
}

TEST(RssCheckpointTest, RefusesALoopTriggeredSearchWithoutItsLoop) {
  ExpectEachRefused({{[](auto& c) { c.mutable_global_searches(0)->set_loop(true); },
                      "triggered by a loop at scan 1, which the loops do not hold"}});
}

TEST(RssProtoTest, GlobalSearchTasksRoundTrip) {
  const std::vector<Pose2> poses = {Pose2(0, 0, 0), Pose2(1, 0.5, 0.1), Pose2(2, 1, 0.2),
                                    Pose2(2.5, 1.5, 0.3)};
  GlobalSearchTask task;
  task.index = 7;
  task.first = 1;
  task.last = 4;
  task.poses = poses;
  task.loop = LoopConstraint{0, 3, Pose2(0.1, -0.2, 0.03)};
  task.max_error = Eigen::Vector3d(0.3, 0.4, 0.05);
  std::vector<Pose2> storage;
  const GlobalSearchTask back = GlobalSearchTaskFromProto(ToProto(task), storage);
  EXPECT_EQ(back.index, 7u);
  EXPECT_EQ(back.first, 1u);
  EXPECT_EQ(back.last, 4u);
  ASSERT_EQ(back.poses.size(), 4u);
  EXPECT_EQ(back.poses[2].translation(), poses[2].translation());
  EXPECT_EQ(back.poses[3].theta(), poses[3].theta());
  ASSERT_TRUE(back.loop.has_value());
  EXPECT_EQ(back.loop->later, 3u);
  EXPECT_EQ(back.loop->relative.translation(), task.loop->relative.translation());
  EXPECT_EQ(back.max_error, task.max_error);
  task.loop.reset();
  EXPECT_FALSE(GlobalSearchTaskFromProto(ToProto(task), storage).loop.has_value());
}

TEST(RssProtoTest, TasksThatDoNotHangTogetherAreRefused) {
  const std::vector<Pose2> poses = {Pose2(), Pose2(1, 0, 0), Pose2(2, 0, 0)};
  GlobalSearchTask task;
  task.first = 1;
  task.last = 3;
  task.poses = poses;
  std::vector<Pose2> storage;
  proto::GlobalSearchSpec spec = ToProto(task);
  spec.set_last(5);  // more scans than poses
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.mutable_y()->RemoveLast();
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.mutable_loop()->set_earlier(2);
  spec.mutable_loop()->set_later(1);
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.set_first(3);
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.mutable_max_error()->RemoveLast();
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
}

}  // namespace
}  // namespace evoslam
