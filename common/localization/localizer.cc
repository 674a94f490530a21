#include "common/localization/localizer.h"

#include <chrono>
#include <cmath>

#include "common/util/error.h"

namespace evoslam {

LocalizeResult Localize(const MapModel& map, const Dataset& dataset, const LocalizeOptions& options,
                        const std::function<void(std::size_t, std::size_t)>& progress) {
  ValidateEstimatorParams(options.estimator);
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  if (options.max_range < 0.0) throw Error("max range must not be negative");
  const auto start_time = std::chrono::steady_clock::now();

  const std::size_t total = options.max_scans > 0
                                ? std::min(options.max_scans, dataset.scans.size())
                                : dataset.scans.size();
  const Rng root(options.seed);
  const double half_diagonal = std::sqrt(0.5) * options.estimator.window;

  LocalizeResult result;
  result.trajectory.reserve(total);
  result.fitness.reserve(total);
  Pose2 previous = options.start.value_or(dataset.scans.front().pose);
  for (std::size_t i = 0; i < total; ++i) {
    const LaserScan& scan = dataset.scans[i];
    Pose2 center = previous;
    if (options.use_odometry && i > 0) {
      center = previous * (dataset.scans[i - 1].odometry.inverse() * scan.odometry);
    }
    const double range =
        options.max_range > 0.0 ? std::min(options.max_range, scan.range_max) : scan.range_max;
    const auto max_range = static_cast<float>(range);
    const auto renderer = map.LocalRenderer(center.translation(), range + half_diagonal);
    Rng rng = root.Stream(i);
    const PoseEstimate estimate =
        EstimatePose(*renderer, scan, center, options.estimator, max_range, rng);
    result.trajectory.push_back({scan.timestamp, estimate.pose});
    result.fitness.push_back(estimate.fitness);
    result.evaluations += estimate.evaluations;
    previous = estimate.pose;
    if (progress) progress(i + 1, total);
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace evoslam
