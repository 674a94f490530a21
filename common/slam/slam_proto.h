#ifndef EVOSLAM_COMMON_SLAM_SLAM_PROTO_H_
#define EVOSLAM_COMMON_SLAM_SLAM_PROTO_H_

#include <cstddef>
#include <string>

#include "common/slam/loop_detector.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// A loop on the wire, and back; the way back throws Error when the loop does not lie within
// scans [0, scans) or lacks its three relative values. `what` names the message it came in.
proto::LoopClosureRecord ToProto(const LoopClosure& loop);
LoopClosure LoopClosureFromProto(const proto::LoopClosureRecord& record, std::size_t scans,
                                 const std::string& what);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_SLAM_PROTO_H_
