#include "common/localization/localizer.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "common/sensor/odometry_stalls.h"
#include "common/util/error.h"

namespace evoslam {

std::size_t ScansToLocalize(const Dataset& dataset, const LocalizeOptions& options) {
  return options.max_scans > 0 ? std::min(options.max_scans, dataset.scans.size())
                               : dataset.scans.size();
}

double ScanMaxRange(const Dataset& dataset, std::size_t scan, const LocalizeOptions& options) {
  const double range_max = dataset.scans.at(scan).range_max;
  return options.max_range > 0.0 ? std::min(options.max_range, range_max) : range_max;
}

ScanWindow WindowOf(const Dataset& dataset, std::size_t scan, const Pose2& previous,
                    const LocalizeOptions& options) {
  ScanWindow w{previous, ScanMaxRange(dataset, scan, options)};
  if (options.use_odometry && scan > 0) {
    w.center =
        previous * (dataset.scans[scan - 1].odometry.inverse() * dataset.scans[scan].odometry);
  }
  return w;
}

namespace {

std::unique_ptr<RangeRenderer> WindowRenderer(const MapModel& map, const Pose2& center,
                                              double max_range, const LocalizeOptions& options) {
  return map.LocalRenderer(center.translation(),
                           max_range + std::sqrt(0.5) * options.estimator.window);
}

// Localize over scans whose odometry stalls, if any, are filled in.
LocalizeResult LocalizeOver(const MapModel& map, const Dataset& dataset,
                            const LocalizeOptions& options, const LocalizeRuntime& runtime) {
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  if (options.max_range < 0.0) throw Error("max range must not be negative");
  const auto start_time = std::chrono::steady_clock::now();

  const std::size_t total = ScansToLocalize(dataset, options);
  const Rng root(options.seed);

  LocalizeState state;
  if (runtime.resume) {
    state = *runtime.resume;
    if (state.next_scan > total || state.done.trajectory.size() != state.next_scan) {
      throw Error("localization checkpoint does not fit the job: it has " +
                  std::to_string(state.done.trajectory.size()) + " poses for scan " +
                  std::to_string(state.next_scan) + " of " + std::to_string(total));
    }
  }
  LocalizeResult& result = state.done;
  result.trajectory.reserve(total);
  result.fitness.reserve(total);
  for (std::size_t i = state.next_scan; i < total; ++i) {
    const LaserScan& scan = dataset.scans[i];
    const Pose2 previous =
        i > 0 ? result.trajectory.back().pose : options.start.value_or(dataset.scans.front().pose);
    const ScanWindow window = WindowOf(dataset, i, previous, options);
    const auto renderer = WindowRenderer(map, window.center, window.max_range, options);
    SearchRuntime search = runtime.search ? runtime.search(i, window.center) : SearchRuntime{};
    search.resume = std::move(state.search);
    state.search.reset();
    if (runtime.checkpoint) {
      search.on_epoch = [&](const ArchipelagoCheckpoint& epoch) {
        state.search = epoch;
        runtime.checkpoint(state);
        state.search.reset();
      };
    }
    Rng rng = root.Stream(i);
    const PoseEstimate estimate = EstimatePose(*renderer, scan, window.center, options.estimator,
                                               static_cast<float>(window.max_range), rng, search);
    result.trajectory.push_back({scan.timestamp, estimate.pose});
    result.fitness.push_back(estimate.fitness);
    result.evaluations += estimate.evaluations;
    state.next_scan = i + 1;
    if (runtime.checkpoint) runtime.checkpoint(state);
    if (runtime.progress) runtime.progress(i + 1, total);
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return std::move(result);
}

}  // namespace

ScanProblem MakeScanProblem(const MapModel& map, const Dataset& dataset, std::size_t scan,
                            const Pose2& center, const LocalizeOptions& options) {
  const double max_range = ScanMaxRange(dataset, scan, options);
  ScanProblem p;
  p.renderer = WindowRenderer(map, center, max_range, options);
  p.problem = MakeScanProblem(*p.renderer, dataset.scans.at(scan), center, options.estimator,
                              static_cast<float>(max_range));
  return p;
}

LocalizeResult Localize(const MapModel& map, const Dataset& dataset, const LocalizeOptions& options,
                        const std::function<void(std::size_t, std::size_t)>& progress) {
  LocalizeRuntime runtime;
  runtime.progress = progress;
  return Localize(map, dataset, options, runtime);
}

std::vector<OdometryStall> OdometryStallsOutsideTheWindow(const Dataset& dataset,
                                                          const LocalizeOptions& options) {
  if (!options.use_odometry) return {};
  const double half = 0.5 * options.estimator.window;
  std::vector<OdometryStall> stalls =
      FindOdometryStalls(dataset.scans, {half, half, options.estimator.heading_half_window});
  const std::size_t n = ScansToLocalize(dataset, options);
  std::erase_if(stalls, [n](const OdometryStall& stall) { return stall.first >= n; });
  return stalls;
}

LocalizeResult Localize(const MapModel& map, const Dataset& dataset, const LocalizeOptions& options,
                        const LocalizeRuntime& runtime) {
  ValidateEstimatorParams(options.estimator);
  std::vector<OdometryStall> stalls = OdometryStallsOutsideTheWindow(dataset, options);
  LocalizeResult result = RunWithOdometryStallsFilled(dataset, stalls, [&](const Dataset& log) {
    return LocalizeOver(map, log, options, runtime);
  });
  result.odometry_stalls = std::move(stalls);
  return result;
}

}  // namespace evoslam
