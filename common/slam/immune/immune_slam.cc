#include "common/slam/immune/immune_slam.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "common/engine/archipelago.h"
#include "common/optim/immune_moea.h"
#include "common/optim/pareto.h"
#include "common/slam/immune/key_points.h"
#include "common/slam/immune/trajectory_segments.h"
#include "common/slam/immune/trajectory_window_problem.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

void RequireProbability(double p, const char* field) {
  if (!(p >= 0.0 && p <= 1.0)) {
    throw Error(fmt::format("immune.search.{} must be in [0, 1], not {}", field, p));
  }
}

// The search as the engine runs it: one island of the immune MOEA with 004's settings, less
// vaccination for the variants without immunity (the problem then offers none).
IslandModelParams SearchModel(const proto::ImmuneSearchParams& s) {
  IslandModelParams model;
  model.islands = 1;
  model.algorithm.kind = AlgorithmKind::kImmune;
  ImmuneMoeaParams& m = model.algorithm.immune;
  m.population = s.population();
  // 004 makes as many children a generation as the population holds, most by recombination.
  m.mutations = std::max<std::size_t>(1, s.population() / 5);
  m.recombinations = s.population() - m.mutations;
  m.p_recombination = s.p_recombination();
  m.p_immunity = s.p_immunity();
  m.p_mutation = s.p_mutation();
  m.archive_size = s.population();
  return model;
}

StopCriteria SearchStop(const proto::ImmuneSearchParams& s) {
  StopCriteria stop;
  stop.max_generations = s.generations();
  stop.stagnation_generations = s.stagnation_generations();
  return stop;
}

// The candidates the search ends with: each island's front (an immune island's includes the
// fronts it archived at its restarts).
Population FinalCandidates(const Archipelago& islands) {
  Population all;
  for (const Island& island : islands.islands()) {
    const auto* immune = dynamic_cast<const ImmuneMoea*>(&island.algorithm());
    const Population p = immune ? immune->Front() : island.algorithm().population();
    const Eigen::Index n = all.x.cols();
    all.x.conservativeResize(p.x.rows(), n + p.x.cols());
    all.f.conservativeResize(p.f.rows(), n + p.f.cols());
    all.x.rightCols(p.x.cols()) = p.x;
    all.f.rightCols(p.f.cols()) = p.f;
  }
  return all;
}

// The member of the front applied: the lowest weighted sum f1 + w2 f2 + w3 f3 (Duckett's fitness,
// which one-objective fronts already hold), the first on ties. The search needs no weights; one
// member must still be chosen, and f1 alone picks the member that spreads the scans farthest apart,
// where the fewest readings can contradict each other (docs/methods/immune.md).
double WeightedSum(const Eigen::Ref<const Eigen::VectorXd>& f,
                   const proto::ImmuneSearchParams& search) {
  if (f.size() == 1) return f[0];
  return DuckettSum(f[0], f[1], f[2], search);
}

std::size_t ChosenMember(const Eigen::MatrixXd& f, const proto::ImmuneSearchParams& search) {
  std::size_t best = 0;
  for (Eigen::Index i = 1; i < f.cols(); ++i) {
    if (WeightedSum(f.col(i), search) <
        WeightedSum(f.col(static_cast<Eigen::Index>(best)), search)) {
      best = static_cast<std::size_t>(i);
    }
  }
  return best;
}

void AddObjectives(const EvidenceObjectives& o, google::protobuf::RepeatedField<double>* out) {
  out->Add(o.consistency);
  out->Add(static_cast<double>(o.occupied));
  out->Add(static_cast<double>(o.empty));
}

// The key points sighted from the window's scans [first, last], with those sightings alone.
std::vector<WindowKeyPoint> KeyPointsOf(std::span<const KeyPoint> key_points, std::size_t first,
                                        std::size_t last) {
  std::vector<WindowKeyPoint> seen;
  for (const KeyPoint& k : key_points) {
    WindowKeyPoint w{.position = k.position, .sightings = {}};
    for (const KeyPointSighting& s : k.sightings) {
      if (s.scan > first && s.scan <= last) w.sightings.push_back(s);
    }
    if (!w.sightings.empty()) seen.push_back(std::move(w));
  }
  return seen;
}

// One scan per key point, the middle of its sightings: the segment around it is short (004 §4:
// 0.2 m at every key point grid). Every sighting would make a real log's segments short wherever
// a corner is in view (Intel: some 6,000 sightings of 225 key points).
std::vector<std::size_t> SightingScans(std::span<const KeyPoint> key_points) {
  std::vector<std::size_t> scans;
  for (const KeyPoint& k : key_points) {
    if (!k.sightings.empty()) scans.push_back(k.sightings[k.sightings.size() / 2].scan);
  }
  std::sort(scans.begin(), scans.end());
  scans.erase(std::unique(scans.begin(), scans.end()), scans.end());
  return scans;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void ValidateImmuneParams(const proto::ImmuneParams& params) {
  ParseImmuneVariant(params.variant());
  if (params.scan_stride() == 0 || params.scan_stride() > 1000) {
    throw Error("immune.scan_stride must be from 1 to 1000, not " +
                std::to_string(params.scan_stride()));
  }
  ValidateEvidenceGridParams(params.evidence());
  ValidateKeyPointParams(params.key_points());
  ValidateTrajectorySegmentParams(params.segments());
  const proto::ImmuneSearchParams& s = params.search();
  if (s.population() < 4 || s.population() > 100000) {
    throw Error("immune.search.population must be from 4 to 100000, not " +
                std::to_string(s.population()));
  }
  RequireProbability(s.p_recombination(), "p_recombination");
  RequireProbability(s.p_immunity(), "p_immunity");
  RequireProbability(s.p_mutation(), "p_mutation");
  RequireProbability(s.accept_worse(), "accept_worse");
  if (s.generations() == 0 || s.generations() > 1000000) {
    throw Error("immune.search.generations must be from 1 to 1000000, not " +
                std::to_string(s.generations()));
  }
  for (const auto& [value, field] : {std::pair{s.occupied_weight(), "occupied_weight"},
                                     std::pair{s.empty_weight(), "empty_weight"}}) {
    if (!IsFiniteNonNegative(value)) {
      throw Error(std::string("immune.search.") + field + " must be finite and not negative");
    }
  }
  ValidateIslandModelParams(SearchModel(s));
}

ImmuneSlamResult RunImmuneSlam(const Dataset& dataset, std::span<const Pose2> initial,
                               const proto::ImmuneParams& params, std::uint64_t seed,
                               const ImmuneSlamRuntime& runtime) {
  const auto start = std::chrono::steady_clock::now();
  ValidateImmuneParams(params);
  const std::size_t n = initial.size();
  const double max_range = params.evidence().max_range_m();

  const std::vector<KeyPoint> key_points =
      FindKeyPoints(dataset, initial, params.key_points(), max_range);
  const SegmentedTrajectory trajectory(
      initial, CutSegments(initial, SightingScans(key_points), params.segments()));
  const auto& segments = trajectory.segments();
  double travelled = 0.0;
  for (const TrajectorySegment& s : segments) travelled += s.length;
  if (segments.empty() || travelled < params.segments().length_m()) {
    throw Error(
        fmt::format("{}: the trajectory of its {} scans travels {:.2f} m, less than one segment "
                    "(immune.segments.length_m = {} m)",
                    dataset.source, n, travelled, params.segments().length_m()));
  }

  std::vector<EvidenceScan> scans;
  scans.reserve(n);
  for (std::size_t k = 0; k < n; ++k) scans.emplace_back(dataset.scans[k], params.evidence());
  std::vector<PlacedScan> at_initial;
  for (std::size_t k = 0; k < n; ++k) at_initial.push_back({&scans[k], initial[k]});
  const GridGeometry geometry = EvidenceGeometryFor(at_initial, params.evidence(), kImmuneGridRoom);

  ImmuneSlamResult result{.poses = {},
                          .map = EvidenceGrid(geometry, params.evidence()),
                          .report = {},
                          .evaluations = 0,
                          .seconds = 0.0};
  proto::ImmuneRunReport& report = result.report;
  report.set_segments(static_cast<std::uint32_t>(segments.size()));
  report.set_key_points(static_cast<std::uint32_t>(key_points.size()));
  {
    EvidenceGrid whole(geometry, params.evidence());
    for (std::size_t k = 0; k < n; k += params.scan_stride()) whole.Add(at_initial[k]);
    AddObjectives(whole.objectives(), report.mutable_start_objectives());
  }

  const std::size_t per_window =
      params.search().window_segments() == 0 ? segments.size() : params.search().window_segments();
  const std::size_t windows = (segments.size() + per_window - 1) / per_window;
  std::vector<SegmentCorrection> corrections(segments.size());
  std::size_t done = 0;
  double seconds_before = 0.0;
  if (runtime.resume != nullptr) {
    const proto::ImmuneCheckpoint& c = *runtime.resume;
    if (c.windows_done() > windows || c.length_size() != c.turn_size() ||
        static_cast<std::size_t>(c.length_size()) !=
            std::min(segments.size(), c.windows_done() * per_window)) {
      throw Error("the job's immune checkpoint does not fit its log and parameters");
    }
    done = c.windows_done();
    for (int j = 0; j < c.length_size(); ++j) {
      corrections[static_cast<std::size_t>(j)] = {.length = c.length(j), .turn = c.turn(j)};
    }
    *report.mutable_windows() = c.windows();
    for (const proto::ImmuneWindowRecord& w : c.windows()) result.evaluations += w.evaluations();
    seconds_before = c.seconds();
  }

  std::vector<Pose2> poses = trajectory.AllPoses(corrections);
  // The map of the windows done: every scan before the next window's first.
  const std::size_t next_first =
      done < windows ? segments[done * per_window].first : trajectory.scans();
  const std::size_t stride = params.scan_stride();
  for (std::size_t k = 0; k < next_first; k += stride) result.map.Add({&scans[k], poses[k]});

  const Rng root(seed);
  const auto progress = [&](std::size_t window, std::size_t generation) {
    if (!runtime.progress) return;
    const std::size_t scans_done = window < windows ? segments[window * per_window].first : n;
    runtime.progress({.done = scans_done,
                      .total = n,
                      .evaluations = result.evaluations,
                      .step = window < windows ? "window " + std::to_string(window + 1) + " of " +
                                                     std::to_string(windows)
                                               : std::string(),
                      .step_done = generation,
                      .step_total = params.search().generations()});
  };
  for (std::size_t w = done; w < windows; ++w) {
    const auto window_start = std::chrono::steady_clock::now();
    const std::size_t first_segment = w * per_window;
    const std::size_t count = std::min(per_window, segments.size() - first_segment);
    const std::size_t first_scan = segments[first_segment].first;
    const std::size_t last_scan = segments[first_segment + count - 1].last;
    TrajectoryWindow window{.trajectory = &trajectory,
                            .scans = scans,
                            .base = &result.map,
                            .first_segment = first_segment,
                            .segments = count,
                            .from = poses[first_scan],
                            .key_points = KeyPointsOf(key_points, first_scan, last_scan)};
    const TrajectoryWindowProblem problem(std::move(window), params);
    const IslandStepper step = LocalIslandStepper(problem);
    Archipelago islands(SearchModel(params.search()), SearchStop(params.search()),
                        root.Stream(w).NextU64());
    progress(w, 0);
    islands.Start(step);
    std::optional<StopReason> stopped;
    while (!(stopped = islands.RunEpoch(step))) {
      progress(w, islands.islands().front().algorithm().generation());
    }

    const Population final_candidates = FinalCandidates(islands);
    const std::vector<std::size_t> front = FirstFront(final_candidates.f);
    Eigen::MatrixXd front_f(final_candidates.f.rows(), static_cast<Eigen::Index>(front.size()));
    for (std::size_t i = 0; i < front.size(); ++i) {
      front_f.col(static_cast<Eigen::Index>(i)) =
          final_candidates.f.col(static_cast<Eigen::Index>(front[i]));
    }
    const std::size_t chosen = ChosenMember(front_f, params.search());
    std::vector<double> start_f(problem.objectives());
    const Eigen::VectorXd none =
        Eigen::VectorXd::Zero(static_cast<Eigen::Index>(problem.dimension()));
    problem.Evaluate(none, start_f);
    // A front that lost every member as good as the window as it stood (crowding can drop one)
    // leaves the window as it stood.
    const bool applied =
        WeightedSum(front_f.col(static_cast<Eigen::Index>(chosen)), params.search()) <=
        WeightedSum(Eigen::Map<const Eigen::VectorXd>(start_f.data(),
                                                      static_cast<Eigen::Index>(start_f.size())),
                    params.search());
    const Eigen::VectorXd best =
        applied ? Eigen::VectorXd(final_candidates.x.col(static_cast<Eigen::Index>(front[chosen])))
                : none;

    proto::ImmuneWindowRecord& record = *report.add_windows();
    record.set_first_segment(static_cast<std::uint32_t>(first_segment));
    record.set_segments(static_cast<std::uint32_t>(count));
    record.set_first_scan(static_cast<std::uint32_t>(first_scan));
    record.set_last_scan(static_cast<std::uint32_t>(last_scan));
    record.set_key_points(static_cast<std::uint32_t>(problem.window().key_points.size()));
    record.set_generations(islands.islands().front().algorithm().generation());
    record.set_evaluations(islands.evaluations());
    if (const auto* immune =
            dynamic_cast<const ImmuneMoea*>(&islands.islands().front().algorithm())) {
      record.set_restarts(static_cast<std::uint32_t>(immune->restarts()));
    }
    record.set_stop(std::string(StopReasonName(*stopped)));
    for (double v : start_f) record.add_start_objectives(v);
    for (Eigen::Index r = 0; r < front_f.rows(); ++r) {
      record.add_chosen_objectives(front_f(r, static_cast<Eigen::Index>(chosen)));
    }
    for (Eigen::Index i = 0; i < front_f.cols(); ++i) {
      for (Eigen::Index r = 0; r < front_f.rows(); ++r) record.add_front(front_f(r, i));
    }
    record.set_chosen(static_cast<std::uint32_t>(chosen));
    record.set_applied(applied);
    record.set_seconds(SecondsSince(window_start));
    result.evaluations += islands.evaluations();

    for (std::size_t j = 0; j < count; ++j) {
      corrections[first_segment + j] = problem.genes().Correction(best, j);
    }
    // The rest of the trajectory moves rigidly with the window's end. Poses are always composed
    // from the start, so that a resumed run composes them as the uninterrupted one did.
    poses = trajectory.AllPoses(corrections);
    // The window's last scan is the next window's first, which that window puts in.
    const std::size_t end = w + 1 < windows ? last_scan : last_scan + 1;
    for (std::size_t k = first_scan; k < end; ++k) {
      if (k % stride == 0) result.map.Add({&scans[k], poses[k]});
    }

    if (runtime.checkpoint) {
      proto::ImmuneCheckpoint checkpoint;
      checkpoint.set_windows_done(static_cast<std::uint32_t>(w + 1));
      for (std::size_t j = 0; j < first_segment + count; ++j) {
        checkpoint.add_length(corrections[j].length);
        checkpoint.add_turn(corrections[j].turn);
      }
      *checkpoint.mutable_windows() = report.windows();
      checkpoint.set_seconds(seconds_before + SecondsSince(start));
      runtime.checkpoint(checkpoint);
    }
  }
  progress(windows, 0);
  AddObjectives(result.map.objectives(), report.mutable_objectives());
  result.poses = std::move(poses);
  result.seconds = seconds_before + SecondsSince(start);
  return result;
}

}  // namespace evoslam
