#ifndef EVOSLAM_COMMON_LOCALIZATION_LOCALIZER_H_
#define EVOSLAM_COMMON_LOCALIZATION_LOCALIZER_H_

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "common/io/trajectory_io.h"
#include "common/localization/map_model.h"
#include "common/localization/pose_estimator.h"
#include "common/sensor/dataset.h"

namespace evoslam {

struct LocalizeOptions {
  EstimatorParams estimator;
  // Centre each window on the odometry prediction instead of the last estimate (the papers use
  // no odometry).
  bool use_odometry = false;
  std::optional<Pose2> start;  // default: the first scan's stated pose
  std::uint64_t seed = 1;
  double max_range = 0.0;     // the simulation's range limit; 0 = each scan's own range_max
  std::size_t max_scans = 0;  // 0 = all
};

struct LocalizeResult {
  std::vector<StampedPose> trajectory;  // one pose per scan
  std::vector<double> fitness;          // the best fitness of each scan
  std::size_t evaluations = 0;
  double seconds = 0.0;
};

// Continual localization in a known map: each scan is matched in a window around the previous
// estimate. Scan i uses random stream i of the seed, so its result depends on the seed and the
// inputs alone. `progress(done, total)` is called after every scan.
LocalizeResult Localize(const MapModel& map, const Dataset& dataset, const LocalizeOptions& options,
                        const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_LOCALIZER_H_
