#ifndef EVOSLAM_COMMON_SLAM_SLAM_PROTO_H_
#define EVOSLAM_COMMON_SLAM_SLAM_PROTO_H_

#include <cstddef>
#include <string>
#include <vector>

#include "common/slam/loop_detector.h"
#include "common/slam/rss_slam.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// A loop on the wire, and back; the way back throws Error when the loop does not lie within
// scans [0, scans) or lacks its three relative values. `what` names the message it came in.
proto::LoopClosureRecord ToProto(const LoopClosure& loop);
LoopClosure LoopClosureFromProto(const proto::LoopClosureRecord& record, std::size_t scans,
                                 const std::string& what);

// A global search task on the wire: the stretch, the poses and the loop.
proto::GlobalSearchSpec ToProto(const GlobalSearchTask& task);
// The task a spec describes; its poses point into `poses`, which it fills. Throws Error when the
// spec does not hang together (a stretch outside its poses, a loop outside the stretch).
GlobalSearchTask GlobalSearchTaskFromProto(const proto::GlobalSearchSpec& spec,
                                           std::vector<Pose2>& poses);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_SLAM_PROTO_H_
