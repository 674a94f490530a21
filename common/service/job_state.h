#ifndef EVOSLAM_COMMON_SERVICE_JOB_STATE_H_
#define EVOSLAM_COMMON_SERVICE_JOB_STATE_H_

#include <string_view>

#include "evoslam/service.pb.h"

namespace evoslam {

// A job that succeeded, failed or was cancelled: it never changes again.
bool IsFinished(proto::JobState state);
// "queued", "running", "succeeded", "failed", "cancelled".
std::string_view JobStateName(proto::JobState state);
// The subcommand that runs a job of this kind: "slam", "localize"; "job" for an unknown kind.
std::string_view JobKindName(proto::JobKind kind);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_JOB_STATE_H_
