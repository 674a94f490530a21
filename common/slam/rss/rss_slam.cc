#include "common/slam/rss/rss_slam.h"

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

void ValidateRssSlamParams(const RssSlamParams& params) {
  ValidateMapParams(params.map());
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
    if (g.generations() == 0 || g.generations() > kMaxGenerations)
      throw Error("global.generations: from 1 to " + std::to_string(kMaxGenerations));
    if (g.islands() == 0 || g.islands() > kMaxIslands)
      throw Error("global.islands: from 1 to " + std::to_string(kMaxIslands));
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

// One run over a log whose odometry stalls are filled, in 002's phases: at every scan a local
// step, then a loop check, and on a loop (or every global.every_scans scans) a global search over
// the stretch behind it, whose correction, if worth it, is applied to the trajectory and the map.
class RssSlamDriver {
 public:
  RssSlamDriver(const Dataset& dataset, const proto::SlamParams& slam,
                const RssSlamRuntime& runtime);
  RssSlamResult Run();

 private:
  // The state to start from: a resumed one once checked against the log's `scans`.
  static RssSlamState StartState(const RssSlamRuntime& runtime, std::size_t scans);
  // Scan i's pose, corrected from odometry's against the map, and inserted into it.
  void LocalStep(std::size_t i);
  // Whether scan i closes a loop, when the detector is due to look.
  std::optional<LoopClosure> LoopCheck(std::size_t i) const;
  // The global search scan `current` starts, or finishes the one the state holds part-way.
  void GlobalSearch(std::size_t current, const std::optional<LoopClosure>& loop);
  // Keeps the search's pick when it is worth it: the stretch's poses, and the map becomes `base`
  // (the problem's, which must stay intact until then) with the stretch's scans at them.
  void Apply(const GlobalSearchProblem& problem, const GlobalSearchTask& task,
             const Population& all, HitCountGrid& base, GlobalSearchRecord& record);
  // The checkpoint first, so that progress never runs ahead of what a resume would start from.
  void ScanDone(std::size_t i);
  void Checkpoint();
  // Scans done, and the global search under way among them, if any.
  void Progress(std::size_t done, std::size_t search_done = 0,
                std::size_t search_generations = 0) const;

  const Dataset& dataset_;
  const RssSlamParams& params_;
  const GlobalSearchParams& global_;
  const RssSlamRuntime& runtime_;
  const std::size_t scans_;
  const Rng root_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  RssSlamState state_;
  const double resumed_total_;
  HitCountGrid map_;
};

RssSlamDriver::RssSlamDriver(const Dataset& dataset, const proto::SlamParams& slam,
                             const RssSlamRuntime& runtime)
    : dataset_(dataset),
      params_(slam.rss()),
      global_(slam.rss().global()),
      runtime_(runtime),
      scans_(ScansToMap(dataset, slam)),
      root_(slam.seed()),
      state_(StartState(runtime, scans_)),
      resumed_total_(state_.times.total),
      map_(BaseMapFor(dataset, state_.poses, 0, 0, slam.rss())) {
  state_.poses.reserve(scans_);
}

RssSlamState RssSlamDriver::StartState(const RssSlamRuntime& runtime, std::size_t scans) {
  if (!runtime.resume) return {};
  const RssSlamState& state = *runtime.resume;
  if (state.next_scan > scans || state.poses.size() != state.next_scan) {
    throw Error("SLAM: the checkpoint does not fit the log (" + std::to_string(state.poses.size()) +
                " poses, next scan " + std::to_string(state.next_scan) + ", " +
                std::to_string(scans) + " scans)");
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
  return state;
}

void RssSlamDriver::Checkpoint() {
  if (!runtime_.checkpoint) return;
  state_.times.total = resumed_total_ + SecondsSince(start_);
  runtime_.checkpoint(state_);
}

void RssSlamDriver::Progress(std::size_t done, std::size_t search_done,
                             std::size_t search_generations) const {
  if (!runtime_.progress) return;
  SlamProgress progress;
  progress.done = done;
  progress.total = scans_;
  progress.evaluations = state_.local_evaluations + state_.global_evaluations;
  if (search_generations > 0) {
    progress.step = "global search";
    progress.step_done = search_done;
    progress.step_total = search_generations;
  }
  runtime_.progress(progress);
}

void RssSlamDriver::ScanDone(std::size_t i) {
  Checkpoint();
  Progress(i + 1);
}

void RssSlamDriver::LocalStep(std::size_t i) {
  const auto start = std::chrono::steady_clock::now();
  const LaserScan& scan = dataset_.scans[i];
  Pose2 pose = scan.odometry;
  if (i > 0) {
    const StepCorrection c =
        CorrectLogStep(map_, dataset_, state_.poses, params_.local(), root_.Stream(i));
    pose = c.pose;
    state_.local_evaluations += c.evaluations;
  }
  map_.AddScan(scan, pose);
  state_.poses.push_back(pose);
  state_.next_scan = i + 1;
  state_.times.local += SecondsSince(start);
}

std::optional<LoopClosure> RssSlamDriver::LoopCheck(std::size_t i) const {
  const bool cooled =
      state_.loops.empty() || i >= state_.last_loop + params_.loops().cooldown_scans();
  if (!cooled || i % params_.loops().check_interval_scans() != 0) return std::nullopt;
  return DetectLoop(dataset_.scans, state_.poses, i, params_.loops());
}

void RssSlamDriver::GlobalSearch(std::size_t current, const std::optional<LoopClosure>& loop) {
  const auto start = std::chrono::steady_clock::now();
  GlobalSearchTask task;
  task.index = state_.global_searches.size();
  task.first = StretchStart(params_, state_, current, loop);
  task.last = current + 1;
  task.poses = state_.poses;
  if (loop) task.loop = loop->constraint;
  task.max_error = GlobalSearchBounds(global_, task.poses, task.loop);
  HitCountGrid base = map_;
  for (std::size_t k = task.first; k < task.last; ++k) {
    base.AddScan(dataset_.scans[k], state_.poses[k], -1);
  }
  const GlobalSearchProblem problem = MakeGlobalSearchProblem(dataset_, task, global_, base);
  const std::size_t generations = global_.generations();
  StopCriteria stop;
  stop.max_generations = generations;
  const IslandStepper step =
      runtime_.global ? runtime_.global(task, problem) : LocalIslandStepper(problem);
  // Islands that do not fit the problem are refused by Island::Evolve.
  Archipelago islands = state_.search ? Archipelago::FromCheckpoint(*state_.search)
                                      : Archipelago(GlobalIslandModel(global_), stop,
                                                    root_.Stream(scans_ + task.index).NextU64());
  if (!state_.search) islands.Start(step);
  state_.search_on_loop = loop.has_value();
  // Scan `current` is done once its search is: until then the run stands at the scans before it.
  const auto search_progress = [&] {
    const std::size_t interval = GlobalIslandModel(global_).migration.interval;
    Progress(current, std::min(generations, islands.epoch() * interval), generations);
  };
  search_progress();
  while (!islands.RunEpoch(step)) {
    if (runtime_.checkpoint) {
      state_.search = islands.Checkpoint();
      Checkpoint();
    }
    search_progress();
  }
  state_.search.reset();
  state_.search_on_loop = false;

  GlobalSearchRecord record;
  record.first = task.first;
  record.last = task.last;
  record.loop = loop;
  record.evaluations = islands.evaluations();
  Apply(problem, task, islands.Merged(), base, record);
  record.seconds = SecondsSince(start);
  state_.global_evaluations += record.evaluations;
  state_.times.global += record.seconds;
  state_.global_searches.push_back(record);
  state_.last_global = current + 1;
}

void RssSlamDriver::Apply(const GlobalSearchProblem& problem, const GlobalSearchTask& task,
                          const Population& all, HitCountGrid& base, GlobalSearchRecord& record) {
  problem.Evaluate(problem.Identity(), record.before);
  const std::optional<std::size_t> pick = PickGlobalSolution(
      all.f, record.before[0] + global_.sharpness_tolerance() * std::abs(record.before[0]));
  // Keep a correction that costs the map at most the tolerance in sharpness and that leaving
  // the stretch alone does not match on both objectives.
  const auto best = static_cast<Eigen::Index>(pick.value_or(0));
  record.after[0] = all.f(0, best);
  record.after[1] = all.f(1, best);
  record.applied = pick && WorthApplying(record.before, record.after,
                                         record.loop ? 0.0 : global_.min_periodic_sharpening());
  if (!record.applied) return;
  const std::vector<Pose2> corrected = problem.Apply(all.x.col(best));
  map_ = std::move(base);
  for (std::size_t k = task.first; k < task.last; ++k) {
    state_.poses[k] = corrected[k - task.first];
    map_.AddScan(dataset_.scans[k], state_.poses[k]);
  }
}

RssSlamResult RssSlamDriver::Run() {
  // A search part-way belongs to the last scan of the state, not done until the search is.
  Progress(state_.search ? state_.next_scan - 1 : state_.next_scan);
  if (state_.search) {
    const std::size_t current = state_.next_scan - 1;
    std::optional<LoopClosure> loop;
    if (state_.search_on_loop) loop = state_.loops.back();
    GlobalSearch(current, loop);
    ScanDone(current);
  }
  for (std::size_t i = state_.next_scan; i < scans_; ++i) {
    LocalStep(i);
    if (global_.enabled()) {
      const auto start = std::chrono::steady_clock::now();
      const std::optional<LoopClosure> loop = LoopCheck(i);
      state_.times.detection += SecondsSince(start);
      if (loop) {
        state_.loops.push_back(*loop);
        state_.last_loop = i;
      }
      const bool periodic =
          global_.every_scans() > 0 && i + 1 - state_.last_global >= global_.every_scans();
      if (loop || periodic) GlobalSearch(i, loop);
    }
    ScanDone(i);
  }

  RssSlamResult result{.trajectory = {},
                       .loops = std::move(state_.loops),
                       .global_searches = std::move(state_.global_searches),
                       .map = std::move(map_),
                       .local_evaluations = state_.local_evaluations,
                       .global_evaluations = state_.global_evaluations,
                       .times = state_.times,
                       .odometry_stalls = {}};
  result.trajectory.reserve(scans_);
  for (std::size_t i = 0; i < scans_; ++i) {
    result.trajectory.push_back({dataset_.scans[i].timestamp, state_.poses[i]});
  }
  result.times.total = resumed_total_ + SecondsSince(start_);
  return result;
}

}  // namespace

RssSlamResult RunRssSlam(const Dataset& dataset, const proto::SlamParams& params,
                         const RssSlamRuntime& runtime) {
  ValidateRssSlamParams(params.rss());
  if (dataset.scans.empty()) throw Error(dataset.source + ": the log has no laser scans");
  // On the readings as logged, so that a jump is named at the scans where it happened and not
  // where filling a stall spread it.
  CheckOdometrySteps(dataset);
  std::vector<OdometryStall> stalls =
      FindOdometryStalls(dataset.scans, BaseErrorCube(params.rss().local()));
  const std::size_t n = ScansToMap(dataset, params);
  std::erase_if(stalls, [n](const OdometryStall& stall) { return stall.first >= n; });
  RssSlamResult result = RunWithOdometryStallsFilled(dataset, stalls, [&](const Dataset& log) {
    return RssSlamDriver(log, params, runtime).Run();
  });
  result.odometry_stalls = std::move(stalls);
  return result;
}

}  // namespace evoslam
