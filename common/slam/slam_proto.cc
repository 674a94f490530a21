#include "common/slam/slam_proto.h"

#include <string>

#include "common/util/error.h"

namespace evoslam {

proto::LoopClosureRecord ToProto(const LoopClosure& loop) {
  proto::LoopClosureRecord p;
  p.set_earlier(static_cast<std::uint32_t>(loop.constraint.earlier));
  p.set_later(static_cast<std::uint32_t>(loop.constraint.later));
  const Pose2& r = loop.constraint.relative;
  for (double v : {r.x(), r.y(), r.theta()}) p.add_relative(v);
  p.set_score(loop.score);
  p.set_distinctness(loop.distinctness);
  return p;
}

LoopClosure LoopClosureFromProto(const proto::LoopClosureRecord& r, std::size_t scans,
                                 const std::string& what) {
  if (r.relative_size() != 3 || !(r.earlier() < r.later()) || r.later() >= scans) {
    throw Error(what + ": the loop from scan " + std::to_string(r.later()) + " back to " +
                std::to_string(r.earlier()) + " with " + std::to_string(r.relative_size()) +
                " relative values does not fit scans [0, " + std::to_string(scans) + ")");
  }
  const LoopConstraint constraint{r.earlier(), r.later(),
                                  Pose2(r.relative(0), r.relative(1), r.relative(2))};
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
