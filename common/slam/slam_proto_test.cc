#include "common/slam/slam_proto.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

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
