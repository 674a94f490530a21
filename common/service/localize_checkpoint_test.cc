#include "common/service/localize_checkpoint.h"

#include <gtest/gtest.h>

#include "common/engine/presets.h"
#include "common/optim/test_problems.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(LocalizeCheckpointTest, RoundTripsEveryPoseAndTheSearchPartWay) {
  LocalizeState state;
  state.next_scan = 2;
  state.done.trajectory = {{1.5, Pose2(0.1, -0.2, 3.0)}, {1.75, Pose2(1.0 / 3, 2.0, -3.1)}};
  state.done.fitness = {10.25, 1.0 / 7};
  state.done.evaluations = 1234;
  IslandModelParams params;
  params.islands = 2;
  params.algorithm = FindPreset("de-000").algorithm;
  StopCriteria stop;
  stop.max_generations = 10;
  Archipelago archipelago(params, stop, 9);
  archipelago.Start(TestFunctionProblem(TestFunction::kSphere, 2));
  state.search = archipelago.Checkpoint();

  proto::LocalizeCheckpoint wire;
  ASSERT_TRUE(wire.ParseFromString(ToProto(state).SerializeAsString()));
  const LocalizeState back = LocalizeStateFromProto(wire);
  EXPECT_EQ(back.next_scan, 2u);
  ASSERT_EQ(back.done.trajectory.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.done.trajectory[i].timestamp, state.done.trajectory[i].timestamp);
    EXPECT_EQ(back.done.trajectory[i].pose.x(), state.done.trajectory[i].pose.x());
    EXPECT_EQ(back.done.trajectory[i].pose.theta(), state.done.trajectory[i].pose.theta());
    EXPECT_EQ(back.done.fitness[i], state.done.fitness[i]);
  }
  EXPECT_EQ(back.done.evaluations, 1234u);
  ASSERT_TRUE(back.search);
  EXPECT_EQ(back.search->islands.size(), 2u);
  EXPECT_EQ(back.search->islands[1].state.population.x,
            state.search->islands[1].state.population.x);
}

TEST(LocalizeCheckpointTest, RefusesColumnsThatDoNotAgree) {
  LocalizeState state;
  state.next_scan = 1;
  state.done.trajectory = {{1.0, Pose2(0, 0, 0)}};
  state.done.fitness = {1.0};
  proto::LocalizeCheckpoint c = ToProto(state);
  c.add_x(5.0);
  EXPECT_THROW(LocalizeStateFromProto(c), Error);
  c = ToProto(state);
  c.set_next_scan(3);
  EXPECT_THROW(LocalizeStateFromProto(c), Error);
}

}  // namespace
}  // namespace evoslam
