#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_IMMUNE_SLAM_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_IMMUNE_SLAM_H_

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/sensor/dataset.h"
#include "common/slam/immune/evidence_grid.h"
#include "common/slam/slam_method.h"
#include "common/transform/pose2.h"
#include "evoslam/slam.pb.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// How far the evidence grid reaches beyond the initial trajectory's scans, m: candidates that carry
// a scan beyond it are infeasible (TrajectoryWindowProblem), so this bounds how far a window may
// move.
inline constexpr double kImmuneGridRoom = 5.0;

// Throws Error naming the first parameter of the immune method out of its range.
void ValidateImmuneParams(const proto::ImmuneParams& params);

// What an immune run needs from where it runs; every member may be left empty.
struct ImmuneSlamRuntime {
  std::function<void(const SlamProgress&)> progress;
  // Called after every window with the run's state.
  std::function<void(const proto::ImmuneCheckpoint&)> checkpoint;
  const proto::ImmuneCheckpoint* resume = nullptr;
};

struct ImmuneSlamResult {
  std::vector<Pose2> poses;  // one per scan mapped
  EvidenceGrid map;          // every scan at its pose
  proto::ImmuneRunReport report;
  std::uint64_t evaluations = 0;
  double seconds = 0.0;
};

// Paper 004's trajectory optimisation over the first `scans` scans of `dataset`, starting from
// `initial` (one laser pose per scan): key points sighted from the initial trajectory, the
// trajectory cut into segments, then each window of window_segments segments searched in turn on
// the map of the windows before it, the member of its final front with the lowest f1 applied.
// Throws Error when the trajectory is too short for one segment.
ImmuneSlamResult RunImmuneSlam(const Dataset& dataset, std::span<const Pose2> initial,
                               const proto::ImmuneParams& params, std::uint64_t seed,
                               const ImmuneSlamRuntime& runtime);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_IMMUNE_SLAM_H_
