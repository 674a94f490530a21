#ifndef EVOSLAM_COMMON_SERVICE_LOCALIZE_INPUTS_H_
#define EVOSLAM_COMMON_SERVICE_LOCALIZE_INPUTS_H_

#include <memory>

#include "common/localization/localizer.h"
#include "common/localization/map_model.h"
#include "common/sensor/dataset.h"
#include "common/service/dataset_files.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// What a localization job works on, read from its datasets: the coordinator loads it once per
// job, a worker once per job it serves.
struct LocalizeInputs {
  LocalizeOptions options;
  Dataset dataset;
  MapModel map;
};

// The datasets of a job (a ProblemSpec's or a JobSpec's references) must already be in `files`.
// Throws Error (InputError for a bad file) naming what is wrong.
std::shared_ptr<const LocalizeInputs> LoadLocalizeInputs(DatasetFiles& files,
                                                         const proto::DatasetRef& log,
                                                         const proto::DatasetRef& map,
                                                         const proto::DatasetRef& map_image,
                                                         const proto::LocalizeParams& params);

// An occupancy grid of a log's reference poses: ground truth where the log has it, else its
// stated poses (localize --map-from-log).
OccupancyGrid GridFromLog(const std::filesystem::path& path, double resolution, bool lenient);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_LOCALIZE_INPUTS_H_
