#include "common/service/job_state.h"

#include <gtest/gtest.h>

namespace evoslam {
namespace {

TEST(JobStateTest, OnlySucceededFailedAndCancelledAreFinal) {
  EXPECT_FALSE(IsFinished(proto::JOB_STATE_QUEUED));
  EXPECT_FALSE(IsFinished(proto::JOB_STATE_RUNNING));
  EXPECT_FALSE(IsFinished(proto::JOB_STATE_UNSPECIFIED));
  EXPECT_TRUE(IsFinished(proto::JOB_STATE_SUCCEEDED));
  EXPECT_TRUE(IsFinished(proto::JOB_STATE_FAILED));
  EXPECT_TRUE(IsFinished(proto::JOB_STATE_CANCELLED));
  EXPECT_EQ(JobStateName(proto::JOB_STATE_CANCELLED), "cancelled");
  EXPECT_EQ(JobStateName(proto::JOB_STATE_UNSPECIFIED), "unknown");
}

TEST(JobStateTest, KindsAreNamedAfterTheirSubcommands) {
  EXPECT_EQ(JobKindName(proto::JOB_KIND_SLAM), "slam");
  EXPECT_EQ(JobKindName(proto::JOB_KIND_LOCALIZE), "localize");
  EXPECT_EQ(JobKindName(proto::JOB_KIND_UNSPECIFIED), "job");
}

}  // namespace
}  // namespace evoslam
