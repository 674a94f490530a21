#ifndef EVOSLAM_COMMON_LOCALIZATION_LOCALIZE_PARAMS_H_
#define EVOSLAM_COMMON_LOCALIZATION_LOCALIZE_PARAMS_H_

#include "common/localization/localizer.h"
#include "evoslam/localize.pb.h"

namespace evoslam {

// A localization's settings in their wire form: what a job carries to the coordinator and its
// workers, and what report.json shows. Every setting the run uses is written exactly (headings
// in radians as well as the degrees people read), so a job decoded elsewhere runs the same bits.
// The names of the map and log, the preset and the map source are left to the caller.
proto::LocalizeParams ToProto(const LocalizeOptions& options);

// The settings a job's parameters describe. Throws Error naming the bad setting.
LocalizeOptions LocalizeOptionsFromProto(const proto::LocalizeParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_LOCALIZE_PARAMS_H_
