#include "common/service/localize_checkpoint.h"

#include <string>

#include "common/engine/engine_proto.h"
#include "common/util/error.h"

namespace evoslam {

proto::LocalizeCheckpoint ToProto(const LocalizeState& state) {
  proto::LocalizeCheckpoint c;
  c.set_next_scan(state.next_scan);
  for (const StampedPose& p : state.done.trajectory) {
    c.add_timestamp(p.timestamp);
    c.add_x(p.pose.x());
    c.add_y(p.pose.y());
    c.add_theta(p.pose.theta());
  }
  for (double f : state.done.fitness) c.add_fitness(f);
  c.set_evaluations(state.done.evaluations);
  if (state.search) *c.mutable_search() = ToProto(*state.search);
  return c;
}

LocalizeState LocalizeStateFromProto(const proto::LocalizeCheckpoint& c) {
  const int n = c.timestamp_size();
  if (c.x_size() != n || c.y_size() != n || c.theta_size() != n || c.fitness_size() != n ||
      c.next_scan() != static_cast<std::uint64_t>(n)) {
    throw Error("localization checkpoint: " + std::to_string(n) + " timestamps, " +
                std::to_string(c.x_size()) + " poses, " + std::to_string(c.fitness_size()) +
                " fitness values for scan " + std::to_string(c.next_scan()));
  }
  LocalizeState state;
  state.next_scan = c.next_scan();
  for (int i = 0; i < n; ++i) {
    state.done.trajectory.push_back({c.timestamp(i), Pose2(c.x(i), c.y(i), c.theta(i))});
    state.done.fitness.push_back(c.fitness(i));
  }
  state.done.evaluations = c.evaluations();
  if (c.has_search()) state.search = FromProto(c.search());
  return state;
}

}  // namespace evoslam
