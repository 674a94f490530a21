#ifndef EVOSLAM_COMMON_LOCALIZATION_LOCALIZER_H_
#define EVOSLAM_COMMON_LOCALIZATION_LOCALIZER_H_

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "common/io/trajectory_io.h"
#include "common/localization/map_model.h"
#include "common/localization/pose_estimator.h"
#include "common/sensor/dataset.h"
#include "common/sensor/odometry_stalls.h"

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
  // The odometry stalls filled in before the search (OdometryStallsOutsideTheWindow).
  std::vector<OdometryStall> odometry_stalls;
};

// A localization between two scans, or part-way through a scan's island search: enough to
// resume it in another process with the same result.
struct LocalizeState {
  std::size_t next_scan = 0;
  LocalizeResult done;                          // the scans before next_scan (seconds excluded)
  std::optional<ArchipelagoCheckpoint> search;  // scan next_scan's island search, part-way
};

// Where the work of a localization runs, and what it reports. The defaults run it here.
struct LocalizeRuntime {
  // The runtime of scan `scan`'s search, centred at `center`; empty: local threads.
  std::function<SearchRuntime(std::size_t scan, const Pose2& center)> search;
  // Called after every scan and every island epoch.
  std::function<void(const LocalizeState&)> checkpoint;
  std::function<void(std::size_t done, std::size_t total)> progress;
  const LocalizeState* resume = nullptr;
};

// The number of scans a localization of `dataset` covers.
std::size_t ScansToLocalize(const Dataset& dataset, const LocalizeOptions& options);

// The search window of scan `scan` when the previous estimate is `previous`: its centre, and the
// range its simulation stops at.
struct ScanWindow {
  Pose2 center;
  double max_range = 0.0;
};
ScanWindow WindowOf(const Dataset& dataset, std::size_t scan, const Pose2& previous,
                    const LocalizeOptions& options);

// The range scan `scan`'s simulation stops at.
double ScanMaxRange(const Dataset& dataset, std::size_t scan, const LocalizeOptions& options);

// Scan `scan`'s search problem with its window centred at `center`, built exactly as Localize
// builds it: what a worker evaluates and evolves for the coordinator.
struct ScanProblem {
  std::unique_ptr<RangeRenderer> renderer;
  std::unique_ptr<Problem> problem;  // refers to *renderer
};
ScanProblem MakeScanProblem(const MapModel& map, const Dataset& dataset, std::size_t scan,
                            const Pose2& center, const LocalizeOptions& options);

// The runs of repeated odometry, among the scans localized, whose catch-up a window centred on the
// odometry's step could not follow (FindOdometryStalls with the window's half-sides); none unless
// options.use_odometry.
std::vector<OdometryStall> OdometryStallsOutsideTheWindow(const Dataset& dataset,
                                                          const LocalizeOptions& options);

// Continual localization in a known map: each scan is matched in a window around the previous
// estimate, or around the odometry's prediction with options.use_odometry; the odometry of the
// stalls above is then filled in first (FillOdometryStalls). Scan i uses random stream i of the
// seed, so its result depends on the seed and the inputs alone, wherever its search runs.
LocalizeResult Localize(const MapModel& map, const Dataset& dataset, const LocalizeOptions& options,
                        const LocalizeRuntime& runtime = {});
LocalizeResult Localize(const MapModel& map, const Dataset& dataset, const LocalizeOptions& options,
                        const std::function<void(std::size_t, std::size_t)>& progress);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_LOCALIZER_H_
