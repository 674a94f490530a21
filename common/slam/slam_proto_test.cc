#include "common/slam/slam_proto.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(SlamProtoTest, GlobalSearchTasksRoundTrip) {
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

TEST(SlamProtoTest, TasksThatDoNotHangTogetherAreRefused) {
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

TEST(SlamProtoTest, LoopsRoundTripAndMustFitTheLog) {
  const LoopClosure loop{LoopConstraint{2, 9, Pose2(0.5, -0.25, 0.125)}, 0.9, 0.2};
  const LoopClosure back = LoopClosureFromProto(ToProto(loop), 10, "test");
  EXPECT_EQ(back.constraint.earlier, 2u);
  EXPECT_EQ(back.constraint.later, 9u);
  EXPECT_EQ(back.constraint.relative.translation(), loop.constraint.relative.translation());
  EXPECT_EQ(back.constraint.relative.theta(), loop.constraint.relative.theta());
  EXPECT_EQ(back.score, 0.9);
  EXPECT_EQ(back.distinctness, 0.2);
  EXPECT_THROW(LoopClosureFromProto(ToProto(loop), 9, "test"), Error);
}

}  // namespace
}  // namespace evoslam
