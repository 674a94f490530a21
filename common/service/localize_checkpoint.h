#ifndef EVOSLAM_COMMON_SERVICE_LOCALIZE_CHECKPOINT_H_
#define EVOSLAM_COMMON_SERVICE_LOCALIZE_CHECKPOINT_H_

#include "common/localization/localizer.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// A localization part-way, in the form the coordinator stores to resume it after a restart.
proto::LocalizeCheckpoint ToProto(const LocalizeState& state);
// Throws Error when the message is inconsistent (columns of different lengths, a bad search).
LocalizeState LocalizeStateFromProto(const proto::LocalizeCheckpoint& checkpoint);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_LOCALIZE_CHECKPOINT_H_
