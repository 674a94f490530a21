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
  if (params.max_stretch > 0 && current + 1 - first > params.max_stretch) {
    first = current + 1 - params.max_stretch;
  }
  return first;
}

}  // namespace

std::size_t ScansToMap(const Dataset& dataset, const RssSlamParams& params) {
  const std::size_t n = dataset.scans.size();
  return params.max_scans > 0 ? std::min(n, params.max_scans) : n;
}

void ValidateRssSlamParams(const RssSlamParams& params) {
  ValidateLocalSearchParams(params.local);
  ValidateGlobalSearchParams(params.global);
  ValidateLoopDetectionParams(params.loops);
  if (!(params.refine_error.array() >= 0.0).all() || !params.refine_error.allFinite() ||
      !(params.loop_bound_scale >= 0.0) || !(params.sharpness_tolerance >= 0.0)) {
    throw Error("global search: the search bounds must be finite and not negative");
  }
  if (!(params.min_periodic_eq6_gain >= 0.0 && params.min_periodic_eq6_gain < 1.0))
    throw Error("global search: the minimum eq. 6 gain without a loop must be in [0, 1)");
  if (!(params.min_eq7_gain >= 0.0 && params.min_eq7_gain < 1.0))
    throw Error("global search: the minimum eq. 7 gain must be in [0, 1)");
  if (params.global_search) {
    if (params.generations == 0) throw Error("global search: at least 1 generation is needed");
    ValidateIslandModelParams(GlobalIslandModel(params));
  }
}

IslandModelParams GlobalIslandModel(const RssSlamParams& params) {
  IslandModelParams model;
  model.islands = params.islands;
  model.algorithm = FindPreset(params.preset).algorithm;
  return model;
}

HitCountGrid BaseMapFor(const Dataset& dataset, std::span<const Pose2> poses, std::size_t first,
                        std::size_t last, const LocalSearchParams& params) {
  HitCountGrid map = EmptyMapFor(dataset, params);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k < first || k >= last) map.AddScan(dataset.scans[k], poses[k]);
  }
  return map;
}

Eigen::Vector3d GlobalSearchBounds(const RssSlamParams& params, std::span<const Pose2> poses,
                                   const std::optional<LoopConstraint>& loop) {
  if (!loop) return params.refine_error;
  const Pose2 expected = poses[loop->earlier] * loop->relative;
  const Pose2 discrepancy = poses[loop->later].inverse() * expected;
  const Eigen::Vector3d size(discrepancy.translation().norm(), discrepancy.translation().norm(),
                             std::abs(discrepancy.theta()));
  return (params.loop_bound_scale * size + params.refine_error).cwiseMin(params.global.max_error);
}

GlobalSearchProblem MakeGlobalSearchProblem(const Dataset& dataset, const GlobalSearchTask& task,
                                            const RssSlamParams& params, const HitCountGrid& base) {
  GlobalSearchParams global = params.global;
  global.max_error = task.max_error;
  if (!task.loop) global.w2 = 0.0;  // 002: a search not started by a loop has no W2 term
  return GlobalSearchProblem(dataset.scans, task.poses, task.first, task.last, base, global,
                             task.loop, task.held);
}

namespace {

// RunRssSlam over a log whose odometry stalls are filled.
RssSlamResult RunOverFilledLog(const Dataset& dataset, const RssSlamParams& params,
                               std::uint64_t seed, const RssSlamRuntime& runtime) {
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  CheckOdometrySteps(dataset);
  const auto run_start = std::chrono::steady_clock::now();
  const std::size_t n = ScansToMap(dataset, params);
  const Rng root(seed);

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
  HitCountGrid map = BaseMapFor(dataset, state.poses, 0, 0, params.local);
  state.poses.reserve(n);

  // Runs the global search scan `current` starts, or finishes the one state.search holds.
  const auto global_search = [&](std::size_t current, const std::optional<LoopClosure>& loop) {
    const auto start = std::chrono::steady_clock::now();
    GlobalSearchTask task;
    task.index = state.global_searches.size();
    task.first = StretchStart(params, state, current, loop);
    task.last = current + 1;
    task.poses = state.poses;
    if (loop) {
      task.loop = loop->constraint;
      if (params.hold_loops) {
        for (std::size_t k = 0; k + 1 < state.loops.size(); ++k) {
          const LoopConstraint& c = state.loops[k].constraint;
          if (c.later >= task.first && c.later < task.last) task.held.push_back(c);
        }
      }
    }
    task.max_error = GlobalSearchBounds(params, task.poses, task.loop);
    HitCountGrid base = map;
    for (std::size_t k = task.first; k < task.last; ++k) {
      base.AddScan(dataset.scans[k], state.poses[k], -1);
    }
    const GlobalSearchProblem problem = MakeGlobalSearchProblem(dataset, task, params, base);
    StopCriteria stop;
    stop.max_generations = params.generations;
    const IslandStepper step =
        runtime.global ? runtime.global(task, problem) : LocalIslandStepper(problem);
    // Islands that do not fit the problem are refused by Island::Evolve.
    Archipelago islands = state.search ? Archipelago::FromCheckpoint(*state.search)
                                       : Archipelago(GlobalIslandModel(params), stop,
                                                     root.Stream(n + task.index).NextU64());
    if (!state.search) islands.Start(step);
    state.search_on_loop = loop.has_value();
    if (runtime.progress) runtime.progress("global search", 0, params.generations);
    while (!islands.RunEpoch(step)) {
      if (runtime.checkpoint) {
        state.search = islands.Checkpoint();
        checkpoint();
      }
      if (runtime.progress) {
        runtime.progress("global search",
                         std::min(params.generations,
                                  islands.epoch() * GlobalIslandModel(params).migration.interval),
                         params.generations);
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
        all.f, record.before[0] + params.sharpness_tolerance * std::abs(record.before[0]));
    // Keep a correction that costs the map at most the tolerance in sharpness and that leaving
    // the stretch alone does not match on both objectives.
    const auto best = static_cast<Eigen::Index>(pick.value_or(0));
    record.after[0] = all.f(0, best);
    record.after[1] = all.f(1, best);
    record.applied =
        pick && WorthApplying(record.before, record.after,
                              loop ? 0.0 : params.min_periodic_eq6_gain, params.min_eq7_gain);
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
          CorrectLogStep(map, dataset, state.poses, params.local, root.Stream(i));
      pose = c.pose;
      state.local_evaluations += c.evaluations;
    }
    map.AddScan(scan, pose);
    state.poses.push_back(pose);
    state.next_scan = i + 1;
    state.times.local += SecondsSince(start);

    if (params.global_search) {
      start = std::chrono::steady_clock::now();
      std::optional<LoopClosure> loop;
      const bool cooled = state.loops.empty() || i >= state.last_loop + params.loops.cooldown;
      if (cooled && i % params.loops.check_interval == 0) {
        loop = DetectLoop(dataset.scans, state.poses, i, params.loops);
      }
      state.times.detection += SecondsSince(start);
      if (loop) {
        state.loops.push_back(*loop);
        state.last_loop = i;
      }
      const bool periodic =
          params.global_every > 0 && i + 1 - state.last_global >= params.global_every;
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

RssSlamResult RunRssSlam(const Dataset& dataset, const RssSlamParams& params, std::uint64_t seed,
                         const RssSlamRuntime& runtime) {
  ValidateRssSlamParams(params);
  std::vector<OdometryStall> stalls = FindOdometryStalls(dataset.scans, params.local.max_error);
  const std::size_t n = ScansToMap(dataset, params);
  std::erase_if(stalls, [n](const OdometryStall& stall) { return stall.first >= n; });
  RssSlamResult result = RunWithOdometryStallsFilled(dataset, stalls, [&](const Dataset& log) {
    return RunOverFilledLog(log, params, seed, runtime);
  });
  result.odometry_stalls = std::move(stalls);
  return result;
}

}  // namespace evoslam
