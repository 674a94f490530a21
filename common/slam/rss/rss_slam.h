#ifndef EVOSLAM_COMMON_SLAM_RSS_RSS_SLAM_H_
#define EVOSLAM_COMMON_SLAM_RSS_RSS_SLAM_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/engine/archipelago.h"
#include "common/grid/hit_count_grid.h"
#include "common/io/trajectory_io.h"
#include "common/sensor/dataset.h"
#include "common/sensor/odometry_stalls.h"
#include "common/slam/loop_detector.h"
#include "common/slam/rss/global_search_problem.h"
#include "common/slam/rss/local_search.h"
#include "common/slam/slam_method.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// Paper 002's whole algorithm: the local search at every step, and the global search over the
// steps since the last one when a loop is detected, or every global.every_scans steps. What each
// parameter does is in proto/evoslam/slam_params.proto and docs/methods/rss.md.
using RssSlamParams = proto::RssParams;

// Beyond this a global search's time, not its search, grows.
inline constexpr std::size_t kMaxGenerations = 1000000;

// Throws Error naming the first parameter out of its range.
void ValidateRssSlamParams(const RssSlamParams& params);

// The island model each global search runs.
IslandModelParams GlobalIslandModel(const GlobalSearchParams& params);

// One global search, as run.
struct GlobalSearchRecord {
  std::size_t first = 0, last = 0;  // scans [first, last)
  std::optional<LoopClosure> loop;  // what triggered it; none: every k steps (W2 = 0)
  bool applied = false;             // the correction was kept
  std::size_t evaluations = 0;
  double seconds = 0.0;
  double before[2] = {0.0, 0.0};  // objectives of leaving the stretch as it was
  double after[2] = {0.0, 0.0};   // objectives of the correction chosen
};

struct SlamPhaseTimes {
  double local = 0.0, detection = 0.0, global = 0.0, total = 0.0;  // s
};

// A SLAM run between two scans or two epochs of a global search: enough to resume it elsewhere
// with the same result (the map is rebuilt from the poses).
struct RssSlamState {
  std::size_t next_scan = 0;
  std::vector<Pose2> poses;  // scans [0, next_scan)
  std::vector<LoopClosure> loops;
  std::vector<GlobalSearchRecord> global_searches;
  std::size_t local_evaluations = 0, global_evaluations = 0;
  std::size_t last_global = 0;  // the first scan the next global search covers
  std::size_t last_loop = 0;    // the scan of the last detected loop (cooldown)
  SlamPhaseTimes times;
  // The global search scan next_scan - 1 started, part-way (its islands after an epoch), and
  // whether the last loop started it: a resume finishes it before the next scan.
  std::optional<ArchipelagoCheckpoint> search;
  bool search_on_loop = false;
};

struct RssSlamResult {
  std::vector<StampedPose> trajectory;  // one pose per scan, the laser's
  std::vector<LoopClosure> loops;
  std::vector<GlobalSearchRecord> global_searches;
  HitCountGrid map;  // every scan at its final pose
  std::size_t local_evaluations = 0, global_evaluations = 0;
  SlamPhaseTimes times;
  // Where the log's odometry stalled while the robot moved; the searches started from it filled
  // (FillOdometryStalls), the trajectory's odometry alone is the log's.
  std::vector<OdometryStall> odometry_stalls;
};

// What a global search's islands need to be rebuilt elsewhere: the stretch, the poses it
// starts from, and the loop.
struct GlobalSearchTask {
  std::size_t index = 0;  // the run's global searches so far
  std::size_t first = 0, last = 0;
  std::span<const Pose2> poses;  // scans [0, last)
  std::optional<LoopConstraint> loop;
  Eigen::Vector3d max_error = Eigen::Vector3d::Zero();  // each partition's, as bounded for this
};

// The bounds of a global search over `poses` for `loop` (none: a periodic search).
Eigen::Vector3d GlobalSearchBounds(const GlobalSearchParams& params, std::span<const Pose2> poses,
                                   const std::optional<LoopConstraint>& loop);

// Where the global searches run and what the run reports. The defaults run it here.
struct RssSlamRuntime {
  // The stepper of a global search's islands; empty: local threads.
  std::function<IslandStepper(const GlobalSearchTask& task, const GlobalSearchProblem& problem)>
      global;
  // After every scan (and the global search it started, if any), before its progress, and
  // after every epoch of a global search.
  std::function<void(const RssSlamState&)> checkpoint;
  // Scans done of all, with a global search under way as the step ("global search",
  // generations done of its generations), and the fitness evaluations so far: once at the
  // start, then after every scan and every epoch of a global search.
  std::function<void(const SlamProgress&)> progress;
  const RssSlamState* resume = nullptr;
};

// The map of every scan other than [first, last), at `poses` (scans [0, poses.size())): the base
// a global search re-inserts its stretch into.
HitCountGrid BaseMapFor(const Dataset& dataset, std::span<const Pose2> poses, std::size_t first,
                        std::size_t last, const RssSlamParams& params);

// The global search problem of a task, exactly as RunRssSlam builds it: what a worker rebuilds.
// `base` must outlive the problem.
GlobalSearchProblem MakeGlobalSearchProblem(const Dataset& dataset, const GlobalSearchTask& task,
                                            const GlobalSearchParams& params,
                                            const HitCountGrid& base);

// Runs the whole algorithm over a log with params.rss(), mapping params.max_scans() scans. Scan
// i's local search draws from random stream i of params.seed() and global search g from stream
// (scans + g), so the result depends on the inputs and the seed alone, wherever the searches run.
// Where the log's odometry stalls with a catch-up beyond the local search's cube
// (FindOdometryStalls), each step starts from the stall filled in.
RssSlamResult RunRssSlam(const Dataset& dataset, const proto::SlamParams& params,
                         const RssSlamRuntime& runtime = {});

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_RSS_RSS_SLAM_H_
