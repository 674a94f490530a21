#include "common/slam/rss/rss_proto.h"

#include <algorithm>
#include <string>

#include "common/engine/engine_proto.h"
#include "common/slam/slam_proto.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

std::string Scans(std::uint64_t first, std::uint64_t last) {
  return "scans [" + std::to_string(first) + ", " + std::to_string(last) + ")";
}

// The record keeps only whether a loop triggered the search; that loop is the one detected at
// the search's last scan, which the checkpoint's loops hold.
GlobalSearchRecord SearchFromProto(const proto::GlobalSearchRecord& r,
                                   const std::vector<LoopClosure>& loops, std::size_t next_scan) {
  if (!(r.first() < r.last()) || r.last() > next_scan || r.before_size() != 2 ||
      r.after_size() != 2) {
    throw Error("SLAM checkpoint: a global search over " + Scans(r.first(), r.last()) + " with " +
                std::to_string(r.before_size()) + " + " + std::to_string(r.after_size()) +
                " objectives does not fit " + Scans(0, next_scan));
  }
  GlobalSearchRecord search{.first = r.first(),
                            .last = r.last(),
                            .loop = std::nullopt,
                            .applied = r.applied(),
                            .evaluations = r.evaluations(),
                            .seconds = r.seconds(),
                            .before = {r.before(0), r.before(1)},
                            .after = {r.after(0), r.after(1)}};
  if (r.loop()) {
    const auto loop = std::find_if(loops.begin(), loops.end(), [&](const LoopClosure& l) {
      return l.constraint.later + 1 == search.last;
    });
    if (loop == loops.end()) {
      throw Error("SLAM checkpoint: the global search over " + Scans(r.first(), r.last()) +
                  " was triggered by a loop at scan " + std::to_string(r.last() - 1) +
                  ", which the loops do not hold");
    }
    search.loop = *loop;
  }
  return search;
}

}  // namespace

proto::GlobalSearchRecord ToProto(const GlobalSearchRecord& search) {
  proto::GlobalSearchRecord p;
  p.set_first(static_cast<std::uint32_t>(search.first));
  p.set_last(static_cast<std::uint32_t>(search.last));
  p.set_loop(search.loop.has_value());
  p.set_applied(search.applied);
  p.set_evaluations(search.evaluations);
  p.set_seconds(search.seconds);
  for (double v : search.before) p.add_before(v);
  for (double v : search.after) p.add_after(v);
  return p;
}

proto::SlamPhaseTimes ToProto(const SlamPhaseTimes& times) {
  proto::SlamPhaseTimes p;
  p.set_local_s(times.local);
  p.set_detection_s(times.detection);
  p.set_global_s(times.global);
  p.set_total_s(times.total);
  return p;
}

proto::RssCheckpoint ToProto(const RssSlamState& state) {
  proto::RssCheckpoint c;
  c.set_next_scan(state.next_scan);
  for (const Pose2& p : state.poses) {
    c.add_x(p.x());
    c.add_y(p.y());
    c.add_theta(p.theta());
  }
  for (const LoopClosure& loop : state.loops) *c.add_loops() = ToProto(loop);
  for (const GlobalSearchRecord& g : state.global_searches) *c.add_global_searches() = ToProto(g);
  c.set_local_evaluations(state.local_evaluations);
  c.set_global_evaluations(state.global_evaluations);
  c.set_last_global(state.last_global);
  c.set_last_loop(state.last_loop);
  *c.mutable_times() = ToProto(state.times);
  if (state.search) *c.mutable_search() = ToProto(*state.search);
  c.set_search_on_loop(state.search_on_loop);
  return c;
}

RssSlamState RssSlamStateFromProto(const proto::RssCheckpoint& c) {
  const std::uint64_t n = c.next_scan();
  if (c.x_size() != c.y_size() || c.x_size() != c.theta_size() ||
      static_cast<std::uint64_t>(c.x_size()) != n) {
    throw Error("SLAM checkpoint: " + std::to_string(c.x_size()) + " x, " +
                std::to_string(c.y_size()) + " y and " + std::to_string(c.theta_size()) +
                " theta values for the " + std::to_string(n) + " scans done");
  }
  if (c.last_global() > n || c.last_loop() > n) {
    throw Error("SLAM checkpoint: the last global search at scan " +
                std::to_string(c.last_global()) + " or the last loop at scan " +
                std::to_string(c.last_loop()) + " lies beyond the " + std::to_string(n) +
                " scans done");
  }
  RssSlamState state;
  state.next_scan = n;
  state.poses.reserve(n);
  for (int i = 0; i < c.x_size(); ++i) state.poses.emplace_back(c.x(i), c.y(i), c.theta(i));
  for (const proto::LoopClosureRecord& loop : c.loops()) {
    state.loops.push_back(LoopClosureFromProto(loop, n, "SLAM checkpoint"));
  }
  for (const proto::GlobalSearchRecord& search : c.global_searches()) {
    state.global_searches.push_back(SearchFromProto(search, state.loops, n));
  }
  state.local_evaluations = c.local_evaluations();
  state.global_evaluations = c.global_evaluations();
  state.last_global = c.last_global();
  state.last_loop = c.last_loop();
  const proto::SlamPhaseTimes& t = c.times();
  state.times = {.local = t.local_s(),
                 .detection = t.detection_s(),
                 .global = t.global_s(),
                 .total = t.total_s()};
  // RunRssSlam refuses a part-way search that no scan or loop of the state started.
  if (c.has_search()) state.search = FromProto(c.search());
  state.search_on_loop = c.search_on_loop();
  return state;
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
  for (int i = 0; i < 3; ++i) spec.add_max_error(task.max_error(i));
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
  if (spec.max_error_size() != 3) {
    throw Error("global search task: 3 error bounds (x, y, theta) are needed, " +
                std::to_string(spec.max_error_size()) + " given");
  }
  task.max_error = {spec.max_error(0), spec.max_error(1), spec.max_error(2)};
  return task;
}

}  // namespace evoslam
