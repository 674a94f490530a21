#ifndef EVOSLAM_COMMON_SLAM_SLAM_PARAMS_H_
#define EVOSLAM_COMMON_SLAM_SLAM_PARAMS_H_

#include <string>
#include <vector>

#include "common/slam/rss_slam.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// A SLAM job's parameters on the wire and in report.json. Unset fields take RssSlamParams'
// defaults (seed 1, method "rss"). Throws Error naming the first bad field.
RssSlamParams RssSlamParamsFromProto(const proto::SlamParams& params);
// The same parameters with every field set to what the run uses.
proto::SlamParams CompleteSlamParams(const proto::SlamParams& params);

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

#endif  // EVOSLAM_COMMON_SLAM_SLAM_PARAMS_H_
