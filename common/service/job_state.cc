#include "common/service/job_state.h"

namespace evoslam {

bool IsFinished(proto::JobState state) {
  return state == proto::JOB_STATE_SUCCEEDED || state == proto::JOB_STATE_FAILED ||
         state == proto::JOB_STATE_CANCELLED;
}

std::string_view JobStateName(proto::JobState state) {
  switch (state) {
    case proto::JOB_STATE_QUEUED:
      return "queued";
    case proto::JOB_STATE_RUNNING:
      return "running";
    case proto::JOB_STATE_SUCCEEDED:
      return "succeeded";
    case proto::JOB_STATE_FAILED:
      return "failed";
    case proto::JOB_STATE_CANCELLED:
      return "cancelled";
    default:
      return "unknown";
  }
}

std::string_view JobKindName(proto::JobKind kind) {
  switch (kind) {
    case proto::JOB_KIND_SLAM:
      return "slam";
    case proto::JOB_KIND_LOCALIZE:
      return "localize";
    default:
      return "job";
  }
}

}  // namespace evoslam
