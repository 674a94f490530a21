#ifndef EVOSLAM_COMMON_REPORT_LOCALIZE_OUTPUTS_H_
#define EVOSLAM_COMMON_REPORT_LOCALIZE_OUTPUTS_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/localization/localizer.h"
#include "common/localization/map_model.h"
#include "common/report/localize_report.h"
#include "common/sensor/dataset.h"
#include "evoslam/localize.pb.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Everything a localization job hands back, as named files: the map it localized in (map.yaml +
// map.pgm for a grid, map.lines for walls), trajectory.txt and trajectory.tum, truth.txt when
// the log has ground truth, map.png (the map with the estimate and the truth, drawn from those
// files as `evoslam plot` draws it), report.json and summary.txt. The coordinator makes them
// once, so a job gives the same files wherever it ran.
std::vector<proto::ResultFile> LocalizeOutputs(const MapModel& map, const Dataset& dataset,
                                               const proto::LocalizeParams& params,
                                               const LocalizeResult& result,
                                               const std::optional<NamedRelations>& relations,
                                               std::uint32_t threads);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_LOCALIZE_OUTPUTS_H_
