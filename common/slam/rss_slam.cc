#include "common/slam/rss_slam.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/engine/presets.h"
#include "common/util/error.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The stretch a global search covers when it runs after scan `current`: the path between a
// loop's two observations, which is what must bend to close it, or else the steps since the
// last global search; at most max_stretch steps.
std::size_t StretchStart(const RssSlamParams& params, const RssSlamState& state,
                         std::size_t current, const std::optional<LoopClosure>& loop) {
  std::size_t first = loop ? loop->constraint.earlier + 1 : state.last_global;
  const std::size_t max_stretch = params.global().max_stretch_scans();
  if (max_stretch > 0 && current + 1 - first > max_stretch) first = current + 1 - max_stretch;
  return first;
}

}  // namespace

std::size_t ScansToMap(const Dataset& dataset, const proto::SlamParams& params) {
  const std::size_t n = dataset.scans.size();
  return params.max_scans() > 0 ? std::min<std::size_t>(n, params.max_scans()) : n;
}

void ValidateRssSlamParams(const RssSlamParams& params) {
  ValidateLocalSearchParams(params.local());
  ValidateGlobalSearchParams(params.global());
  ValidateLoopDetectionParams(params.loops());
  const GlobalSearchParams& g = params.global();
  const Eigen::Vector3d refine = RefineBounds(g);
  if (!(refine.array() >= 0.0).all() || !refine.allFinite())
    throw Error("global.refine_bound_*: must be finite and not negative");
  if (!(g.loop_bound_scale() >= 0.0) || !std::isfinite(g.loop_bound_scale()))
    throw Error("global.loop_bound_scale: must be finite and not negative");
  if (!(g.sharpness_tolerance() >= 0.0) || !std::isfinite(g.sharpness_tolerance()))
    throw Error("global.sharpness_tolerance: must be finite and not negative");
  if (!(g.min_periodic_sharpening() >= 0.0 && g.min_periodic_sharpening() < 1.0))
    throw Error("global.min_periodic_sharpening: must be in [0, 1)");
  if (g.enabled()) {
    if (g.generations() == 0) throw Error("global.generations: at least 1");
    ValidateIslandModelParams(GlobalIslandModel(g));
  }
}

IslandModelParams GlobalIslandModel(const GlobalSearchParams& params) {
  IslandModelParams model;
  model.islands = params.islands();
  model.algorithm = FindPreset(params.preset()).algorithm;
  return model;
}

HitCountGrid BaseMapFor(const Dataset& dataset, std::span<const Pose2> poses, std::size_t first,
                        std::size_t last, const RssSlamParams& params) {
  HitCountGrid map = EmptyMapFor(dataset, params.map(), params.local());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k < first || k >= last) map.AddScan(dataset.scans[k], poses[k]);
  }
  return map;
}

Eigen::Vector3d GlobalSearchBounds(const GlobalSearchParams& params, std::span<const Pose2> poses,
                                   const std::optional<LoopConstraint>& loop) {
  if (!loop) return RefineBounds(params);
  const Pose2 expected = poses[loop->earlier] * loop->relative;
  const Pose2 discrepancy = poses[loop->later].inverse() * expected;
  const Eigen::Vector3d size(discrepancy.translation().norm(), discrepancy.translation().norm(),
                             std::abs(discrepancy.theta()));
  return (params.loop_bound_scale() * size + RefineBounds(params))
      .cwiseMin(PartitionErrorBounds(params));
}

GlobalSearchProblem MakeGlobalSearchProblem(const Dataset& dataset, const GlobalSearchTask& task,
                                            const GlobalSearchParams& params,
                                            const HitCountGrid& base) {
  return GlobalSearchProblem(dataset.scans, task.poses, task.first, task.last, base, params,
                             task.max_error, task.loop);
}

namespace {

// RunRssSlam over a log whose odometry stalls are filled.
RssSlamResult RunOverFilledLog(const Dataset& dataset, const proto::SlamParams& slam,
                               const RssSlamRuntime& runtime) {
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  CheckOdometrySteps(dataset);
  const auto run_start = std::chrono::steady_clock::now();
  const RssSlamParams& params = slam.rss();
  const GlobalSearchParams& global = params.global();
  const std::size_t n = ScansToMap(dataset, slam);
  const Rng root(slam.seed());

  RssSlamState state = runtime.resume ? *runtime.resume : RssSlamState{};
  if (state.next_scan > n || state.poses.size() != state.next_scan) {
    throw Error("SLAM: the checkpoint does not fit the log (" + std::to_string(state.poses.size()) +
                " poses, next scan " + std::to_string(state.next_scan) + ", " + std::to_string(n) +
                " scans)");
  }
  const bool search_fits =
      !state.search ||
      (state.next_scan > 0 &&
       (!state.search_on_loop ||
        (!state.loops.empty() && state.loops.back().constraint.later + 1 == state.next_scan)));
  if (!search_fits) {
    throw Error(
        "SLAM: the checkpoint's part-way global search was started by no scan or loop it "
        "holds (next scan " +
        std::to_string(state.next_scan) + ", " + std::to_string(state.loops.size()) + " loops)");
  }
  const double resumed_total = state.times.total;
  // Hands the state as it stands to the runtime, its total time brought up to date.
  const auto checkpoint = [&] {
    if (!runtime.checkpoint) return;
    state.times.total = resumed_total + SecondsSince(run_start);
    runtime.checkpoint(state);
  };
  HitCountGrid map = BaseMapFor(dataset, state.poses, 0, 0, params);
  state.poses.reserve(n);

  // Runs the global search scan `current` starts, or finishes the one state.search holds.
  const auto global_search = [&](std::size_t current, const std::optional<LoopClosure>& loop) {
    const auto start = std::chrono::steady_clock::now();
    GlobalSearchTask task;
    task.index = state.global_searches.size();
    task.first = StretchStart(params, state, current, loop);
    task.last = current + 1;
    task.poses = state.poses;
    if (loop) task.loop = loop->constraint;
    task.max_error = GlobalSearchBounds(global, task.poses, task.loop);
    HitCountGrid base = map;
    for (std::size_t k = task.first; k < task.last; ++k) {
      base.AddScan(dataset.scans[k], state.poses[k], -1);
    }
    const GlobalSearchProblem problem = MakeGlobalSearchProblem(dataset, task, global, base);
    const std::size_t generations = global.generations();
    StopCriteria stop;
    stop.max_generations = generations;
    const IslandStepper step =
        runtime.global ? runtime.global(task, problem) : LocalIslandStepper(problem);
    // Islands that do not fit the problem are refused by Island::Evolve.
    Archipelago islands = state.search ? Archipelago::FromCheckpoint(*state.search)
                                       : Archipelago(GlobalIslandModel(global), stop,
                                                     root.Stream(n + task.index).NextU64());
    if (!state.search) islands.Start(step);
    state.search_on_loop = loop.has_value();
    if (runtime.progress) runtime.progress("global search", 0, generations);
    while (!islands.RunEpoch(step)) {
      if (runtime.checkpoint) {
        state.search = islands.Checkpoint();
        checkpoint();
      }
      if (runtime.progress) {
        runtime.progress(
            "global search",
            std::min(generations, islands.epoch() * GlobalIslandModel(global).migration.interval),
            generations);
      }
    }
    state.search.reset();
    state.search_on_loop = false;
    const Population all = islands.Merged();

    GlobalSearchRecord record;
    record.first = task.first;
    record.last = task.last;
    record.loop = loop;
    record.evaluations = islands.evaluations();
    problem.Evaluate(problem.Identity(), record.before);
    const std::optional<std::size_t> pick = PickGlobalSolution(
        all.f, record.before[0] + global.sharpness_tolerance() * std::abs(record.before[0]));
    // Keep a correction that costs the map at most the tolerance in sharpness and that leaving
    // the stretch alone does not match on both objectives.
    const auto best = static_cast<Eigen::Index>(pick.value_or(0));
    record.after[0] = all.f(0, best);
    record.after[1] = all.f(1, best);
    record.applied = pick && WorthApplying(record.before, record.after,
                                           loop ? 0.0 : global.min_periodic_sharpening());
    if (record.applied) {
      const std::vector<Pose2> corrected = problem.Apply(all.x.col(best));
      map = std::move(base);
      for (std::size_t k = task.first; k < task.last; ++k) {
        state.poses[k] = corrected[k - task.first];
        map.AddScan(dataset.scans[k], state.poses[k]);
      }
    }
    record.seconds = SecondsSince(start);
    state.global_evaluations += record.evaluations;
    state.times.global += record.seconds;
    state.global_searches.push_back(record);
    state.last_global = current + 1;
  };

  // The checkpoint first, so that progress never runs ahead of what a resume would start from.
  const auto scan_done = [&](std::size_t i) {
    checkpoint();
    if (runtime.progress) runtime.progress("local search", i + 1, n);
  };
  if (state.search) {
    const std::size_t current = state.next_scan - 1;
    std::optional<LoopClosure> loop;
    if (state.search_on_loop) loop = state.loops.back();
    global_search(current, loop);
    scan_done(current);
  }

  for (std::size_t i = state.next_scan; i < n; ++i) {
    const LaserScan& scan = dataset.scans[i];
    auto start = std::chrono::steady_clock::now();
    Pose2 pose = scan.odometry;
    if (i > 0) {
      const StepCorrection c =
          CorrectLogStep(map, dataset, state.poses, params.local(), root.Stream(i));
      pose = c.pose;
      state.local_evaluations += c.evaluations;
    }
    map.AddScan(scan, pose);
    state.poses.push_back(pose);
    state.next_scan = i + 1;
    state.times.local += SecondsSince(start);

    if (global.enabled()) {
      start = std::chrono::steady_clock::now();
      std::optional<LoopClosure> loop;
      const bool cooled =
          state.loops.empty() || i >= state.last_loop + params.loops().cooldown_scans();
      if (cooled && i % params.loops().check_interval_scans() == 0) {
        loop = DetectLoop(dataset.scans, state.poses, i, params.loops());
      }
      state.times.detection += SecondsSince(start);
      if (loop) {
        state.loops.push_back(*loop);
        state.last_loop = i;
      }
      const bool periodic =
          global.every_scans() > 0 && i + 1 - state.last_global >= global.every_scans();
      if (loop || periodic) global_search(i, loop);
    }
    scan_done(i);
  }

  RssSlamResult result{.trajectory = {},
                       .loops = std::move(state.loops),
                       .global_searches = std::move(state.global_searches),
                       .map = std::move(map),
                       .local_evaluations = state.local_evaluations,
                       .global_evaluations = state.global_evaluations,
                       .times = state.times,
                       .odometry_stalls = {}};
  result.trajectory.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    result.trajectory.push_back({dataset.scans[i].timestamp, state.poses[i]});
  }
  result.times.total = resumed_total + SecondsSince(run_start);
  return result;
}

}  // namespace

RssSlamResult RunRssSlam(const Dataset& dataset, const proto::SlamParams& params,
                         const RssSlamRuntime& runtime) {
  ValidateRssSlamParams(params.rss());
  std::vector<OdometryStall> stalls =
      FindOdometryStalls(dataset.scans, BaseErrorCube(params.rss().local()));
  const std::size_t n = ScansToMap(dataset, params);
  std::erase_if(stalls, [n](const OdometryStall& stall) { return stall.first >= n; });
  RssSlamResult result = RunWithOdometryStallsFilled(
      dataset, stalls, [&](const Dataset& log) { return RunOverFilledLog(log, params, runtime); });
  result.odometry_stalls = std::move(stalls);
  return result;
}

}  // namespace evoslam
