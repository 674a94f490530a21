#include "common/service/slam_checkpoint.h"

#include <algorithm>
#include <string>

#include "common/engine/engine_proto.h"
#include "common/report/slam_report.h"
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

proto::SlamCheckpoint ToProto(const RssSlamState& state) {
  proto::SlamCheckpoint c;
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

RssSlamState RssSlamStateFromProto(const proto::SlamCheckpoint& c) {
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

}  // namespace evoslam
