#include "common/slam/slam_params.h"

#include <cmath>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

Eigen::Vector3d Triple(const google::protobuf::RepeatedField<double>& values,
                       const Eigen::Vector3d& fallback, const char* name) {
  if (values.empty()) return fallback;
  if (values.size() != 3) {
    throw Error(std::string("SLAM parameter ") + name + ": 3 values (x, y, theta) are needed, " +
                std::to_string(values.size()) + " given");
  }
  return {values[0], values[1], values[2]};
}

void SetTriple(google::protobuf::RepeatedField<double>* out, const Eigen::Vector3d& v) {
  out->Clear();
  for (int i = 0; i < 3; ++i) out->Add(v(i));
}

}  // namespace

RssSlamParams RssSlamParamsFromProto(const proto::SlamParams& p) {
  if (p.has_method() && p.method() != "rss") {
    throw Error("SLAM method '" + p.method() + "' is not known (rss)");
  }
  RssSlamParams r;
  if (p.has_max_scans()) r.max_scans = p.max_scans();
  LocalSearchParams& l = r.local;
  if (p.has_local_fitness()) l.fitness = ParseLocalFitness(p.local_fitness());
  l.max_error = Triple(p.local_max_error(), l.max_error, "local_max_error");
  if (p.has_local_particles()) l.particles = p.local_particles();
  if (p.has_local_iterations()) l.iterations = p.local_iterations();
  if (p.has_local_inertia()) l.inertia = p.local_inertia();
  if (p.has_local_c1()) l.c1 = p.local_c1();
  if (p.has_local_c2()) l.c2 = p.local_c2();
  if (p.has_resolution_m()) l.resolution = p.resolution_m();
  if (p.has_margin_m()) l.margin = p.margin_m();
  if (p.has_local_recentres()) l.recentres = p.local_recentres();
  if (p.has_local_frontier_margin_m()) l.frontier_margin = p.local_frontier_margin_m();
  if (p.has_local_odometry_pull()) l.odometry_pull = p.local_odometry_pull();
  if (p.has_local_min_constraint_ratio()) l.min_constraint_ratio = p.local_min_constraint_ratio();
  if (p.has_local_odometry_weight()) l.odometry_weight = p.local_odometry_weight();
  if (p.has_local_free_frontier()) l.free_frontier = p.local_free_frontier();
  if (p.has_local_turn_error_per_rad()) l.turn_error_per_rad = p.local_turn_error_per_rad();
  if (p.has_local_carried_turn_error()) l.carried_turn_error = p.local_carried_turn_error();
  if (p.has_local_carried_turn_shift()) l.carried_turn_shift = p.local_carried_turn_shift();
  if (p.has_local_hedged_shift_rad()) l.hedged_shift = p.local_hedged_shift_rad();
  if (p.has_local_refine_iterations()) l.refine.iterations = p.local_refine_iterations();
  if (p.has_local_refine_max_shift_cells())
    l.refine.max_shift_cells = p.local_refine_max_shift_cells();
  if (p.has_local_refine_max_turn_rad()) l.refine.max_turn = p.local_refine_max_turn_rad();
  if (p.has_local_refine_wall_share()) l.refine.wall_share = p.local_refine_wall_share();
  if (p.has_local_only()) r.global_search = !p.local_only();
  if (p.has_global_every()) r.global_every = p.global_every();
  GlobalSearchParams& g = r.global;
  if (p.has_partitions()) g.partitions = p.partitions();
  g.max_error = Triple(p.global_max_error(), g.max_error, "global_max_error");
  g.sigma = Triple(p.sigma(), g.sigma, "sigma");
  if (p.has_w1()) g.w1 = p.w1();
  if (p.has_w2()) g.w2 = p.w2();
  if (p.has_global_beam_stride()) g.beam_stride = p.global_beam_stride();
  if (p.has_global_scored_scans()) g.scored_scans = p.global_scored_scans();
  if (p.has_generations()) r.generations = p.generations();
  if (p.has_islands()) r.islands = p.islands();
  if (p.has_preset()) r.preset = p.preset();
  if (p.has_max_stretch()) r.max_stretch = p.max_stretch();
  r.refine_error = Triple(p.refine_error(), r.refine_error, "refine_error");
  if (p.has_loop_bound_scale()) r.loop_bound_scale = p.loop_bound_scale();
  if (p.has_sharpness_tolerance()) r.sharpness_tolerance = p.sharpness_tolerance();
  if (p.has_min_eq7_gain()) r.min_eq7_gain = p.min_eq7_gain();
  if (p.has_hold_loops()) r.hold_loops = p.hold_loops();
  if (p.has_min_periodic_eq6_gain()) r.min_periodic_eq6_gain = p.min_periodic_eq6_gain();
  LoopDetectionParams& d = r.loops;
  if (p.has_revisit_radius_m()) d.revisit_radius = p.revisit_radius_m();
  if (p.has_min_gap_scans()) d.min_gap = p.min_gap_scans();
  if (p.has_min_travel_m()) d.min_travel = p.min_travel_m();
  if (p.has_match_window_m()) d.match_window = p.match_window_m();
  if (p.has_match_window_rad()) d.match_window_theta = p.match_window_rad();
  if (p.has_match_window_per_m()) d.match_window_per_metre = p.match_window_per_m();
  if (p.has_max_match_window_m()) d.max_match_window = p.max_match_window_m();
  if (p.has_min_match_score()) d.min_score = p.min_match_score();
  if (p.has_fit_tolerance_m()) d.fit_tolerance = p.fit_tolerance_m();
  if (p.has_fit_tolerance_rad()) d.fit_tolerance_theta = p.fit_tolerance_rad();
  if (p.has_place_scans()) d.place_scans = p.place_scans();
  if (p.has_cooldown_scans()) d.cooldown = p.cooldown_scans();
  if (p.has_check_interval_scans()) d.check_interval = p.check_interval_scans();
  if (p.has_min_distinctness()) d.min_distinctness = p.min_distinctness();
  if (p.has_fit_score_margin()) d.fit_score_margin = p.fit_score_margin();
  if (p.has_min_side_agreement()) d.min_side_agreement = p.min_side_agreement();
  if (p.has_rival_distance_m()) d.rival_distance = p.rival_distance_m();
  if (p.has_match_spread_score()) d.spread_score = p.match_spread_score();
  if (p.has_match_spread_in_eq7()) d.spread_weights_eq7 = p.match_spread_in_eq7();
  ValidateRssSlamParams(r);
  return r;
}

proto::SlamParams CompleteSlamParams(const proto::SlamParams& given) {
  const RssSlamParams r = RssSlamParamsFromProto(given);
  proto::SlamParams p = given;
  p.set_method("rss");
  p.set_seed(given.has_seed() ? given.seed() : 1);
  p.set_lenient(given.lenient());
  p.set_log(given.log());
  p.set_max_scans(static_cast<std::uint32_t>(r.max_scans));
  const LocalSearchParams& l = r.local;
  p.set_local_fitness(std::string(LocalFitnessName(l.fitness)));
  SetTriple(p.mutable_local_max_error(), l.max_error);
  p.set_local_particles(static_cast<std::uint32_t>(l.particles));
  p.set_local_iterations(static_cast<std::uint32_t>(l.iterations));
  p.set_local_inertia(l.inertia);
  p.set_local_c1(l.c1);
  p.set_local_c2(l.c2);
  p.set_resolution_m(l.resolution);
  p.set_margin_m(l.margin);
  p.set_local_recentres(static_cast<std::uint32_t>(l.recentres));
  p.set_local_frontier_margin_m(l.frontier_margin);
  p.set_local_odometry_pull(l.odometry_pull);
  p.set_local_min_constraint_ratio(l.min_constraint_ratio);
  p.set_local_odometry_weight(l.odometry_weight);
  p.set_local_free_frontier(l.free_frontier);
  p.set_local_turn_error_per_rad(l.turn_error_per_rad);
  p.set_local_carried_turn_error(l.carried_turn_error);
  p.set_local_carried_turn_shift(l.carried_turn_shift);
  p.set_local_hedged_shift_rad(l.hedged_shift);
  p.set_local_refine_iterations(static_cast<std::uint32_t>(l.refine.iterations));
  p.set_local_refine_max_shift_cells(l.refine.max_shift_cells);
  p.set_local_refine_max_turn_rad(l.refine.max_turn);
  p.set_local_refine_wall_share(l.refine.wall_share);
  p.set_local_only(!r.global_search);
  p.set_global_every(static_cast<std::uint32_t>(r.global_every));
  const GlobalSearchParams& g = r.global;
  p.set_partitions(static_cast<std::uint32_t>(g.partitions));
  SetTriple(p.mutable_global_max_error(), g.max_error);
  SetTriple(p.mutable_sigma(), g.sigma);
  p.set_w1(g.w1);
  p.set_w2(g.w2);
  p.set_global_beam_stride(static_cast<std::uint32_t>(g.beam_stride));
  p.set_global_scored_scans(static_cast<std::uint32_t>(g.scored_scans));
  p.set_generations(static_cast<std::uint32_t>(r.generations));
  p.set_islands(static_cast<std::uint32_t>(r.islands));
  p.set_preset(r.preset);
  p.set_max_stretch(static_cast<std::uint32_t>(r.max_stretch));
  SetTriple(p.mutable_refine_error(), r.refine_error);
  p.set_loop_bound_scale(r.loop_bound_scale);
  p.set_sharpness_tolerance(r.sharpness_tolerance);
  p.set_min_eq7_gain(r.min_eq7_gain);
  p.set_hold_loops(r.hold_loops);
  p.set_min_periodic_eq6_gain(r.min_periodic_eq6_gain);
  const LoopDetectionParams& d = r.loops;
  p.set_revisit_radius_m(d.revisit_radius);
  p.set_min_gap_scans(static_cast<std::uint32_t>(d.min_gap));
  p.set_min_travel_m(d.min_travel);
  p.set_match_window_m(d.match_window);
  p.set_match_window_rad(d.match_window_theta);
  p.set_match_window_per_m(d.match_window_per_metre);
  p.set_max_match_window_m(d.max_match_window);
  p.set_min_match_score(d.min_score);
  p.set_fit_tolerance_m(d.fit_tolerance);
  p.set_fit_tolerance_rad(d.fit_tolerance_theta);
  p.set_place_scans(static_cast<std::uint32_t>(d.place_scans));
  p.set_cooldown_scans(static_cast<std::uint32_t>(d.cooldown));
  p.set_check_interval_scans(static_cast<std::uint32_t>(d.check_interval));
  p.set_min_distinctness(d.min_distinctness);
  p.set_fit_score_margin(d.fit_score_margin);
  p.set_min_side_agreement(d.min_side_agreement);
  p.set_rival_distance_m(d.rival_distance);
  p.set_match_spread_score(d.spread_score);
  p.set_match_spread_in_eq7(d.spread_weights_eq7);
  return p;
}

proto::LoopClosureRecord ToProto(const LoopClosure& loop) {
  proto::LoopClosureRecord p;
  p.set_earlier(static_cast<std::uint32_t>(loop.constraint.earlier));
  p.set_later(static_cast<std::uint32_t>(loop.constraint.later));
  const Pose2& r = loop.constraint.relative;
  for (double v : {r.x(), r.y(), r.theta()}) p.add_relative(v);
  p.set_score(loop.score);
  p.set_distinctness(loop.distinctness);
  const Eigen::Matrix2d& w = loop.constraint.weight;
  if (w != Eigen::Matrix2d::Identity()) {
    for (double v : {w(0, 0), w(0, 1), w(1, 1)}) p.add_weight(v);
  }
  return p;
}

LoopClosure LoopClosureFromProto(const proto::LoopClosureRecord& r, std::size_t scans,
                                 const std::string& what) {
  if (r.relative_size() != 3 || !(r.earlier() < r.later()) || r.later() >= scans) {
    throw Error(what + ": the loop from scan " + std::to_string(r.later()) + " back to " +
                std::to_string(r.earlier()) + " with " + std::to_string(r.relative_size()) +
                " relative values does not fit scans [0, " + std::to_string(scans) + ")");
  }
  LoopConstraint constraint{r.earlier(), r.later(),
                            Pose2(r.relative(0), r.relative(1), r.relative(2))};
  if (r.weight_size() != 0) {
    const auto& w = r.weight();
    // Symmetric, positive semi-definite, largest eigenvalue 1 (LoopWeight): anything else would
    // reward a miss or count it more than 002's distance.
    const bool valid = r.weight_size() == 3 && w[0] >= 0.0 && w[2] >= 0.0 &&
                       w[0] * w[2] >= w[1] * w[1] &&
                       0.5 * (w[0] + w[2] + std::hypot(w[0] - w[2], 2.0 * w[1])) <= 1.0 + 1e-9;
    if (!valid) {
      throw Error(what + ": the loop from scan " + std::to_string(r.later()) + " back to " +
                  std::to_string(r.earlier()) +
                  " has a weight that is not 3 values (xx, xy, yy) of a positive semi-definite "
                  "matrix no larger than the identity");
    }
    constraint.weight << w[0], w[1], w[1], w[2];
  }
  return {constraint, r.score(), r.distinctness()};
}

proto::GlobalSearchSpec ToProto(const GlobalSearchTask& task) {
  proto::GlobalSearchSpec spec;
  spec.set_index(task.index);
  spec.set_first(task.first);
  spec.set_last(task.last);
  for (std::size_t k = 0; k < task.last && k < task.poses.size(); ++k) {
    spec.add_x(task.poses[k].x());
    spec.add_y(task.poses[k].y());
    spec.add_theta(task.poses[k].theta());
  }
  if (task.loop) *spec.mutable_loop() = ToProto(LoopClosure{*task.loop, 0.0, 0.0});
  for (const LoopConstraint& h : task.held) *spec.add_held() = ToProto(LoopClosure{h, 0.0, 0.0});
  SetTriple(spec.mutable_max_error(), task.max_error);
  return spec;
}

GlobalSearchTask GlobalSearchTaskFromProto(const proto::GlobalSearchSpec& spec,
                                           std::vector<Pose2>& poses) {
  const auto n = static_cast<std::size_t>(spec.x_size());
  if (spec.y_size() != spec.x_size() || spec.theta_size() != spec.x_size()) {
    throw Error("global search task: x, y and theta differ in length");
  }
  if (!(spec.first() < spec.last()) || spec.last() != n) {
    throw Error("global search task: scans [" + std::to_string(spec.first()) + ", " +
                std::to_string(spec.last()) + ") with " + std::to_string(n) + " poses");
  }
  poses.clear();
  poses.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<int>(k);
    poses.emplace_back(spec.x(i), spec.y(i), spec.theta(i));
  }
  GlobalSearchTask task;
  task.index = spec.index();
  task.first = spec.first();
  task.last = spec.last();
  task.poses = poses;
  if (spec.has_loop())
    task.loop = LoopClosureFromProto(spec.loop(), n, "global search task").constraint;
  for (const proto::LoopClosureRecord& h : spec.held()) {
    const LoopConstraint held = LoopClosureFromProto(h, n, "global search task").constraint;
    if (held.later < task.first) {
      throw Error("global search task: the held loop from scan " + std::to_string(held.later) +
                  " ends before the scans searched, [" + std::to_string(task.first) + ", " +
                  std::to_string(task.last) + ")");
    }
    task.held.push_back(held);
  }
  task.max_error = Triple(spec.max_error(), Eigen::Vector3d::Zero(), "max_error");
  return task;
}

}  // namespace evoslam
