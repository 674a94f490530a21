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

}  // namespace evoslam
