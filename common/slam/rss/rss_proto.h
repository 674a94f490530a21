#ifndef EVOSLAM_COMMON_SLAM_RSS_RSS_PROTO_H_
#define EVOSLAM_COMMON_SLAM_RSS_RSS_PROTO_H_

#include <vector>

#include "common/slam/rss/rss_slam.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// The rss method's messages: what it reports, what it keeps of a run part-way, and what it
// sends its workers.

proto::GlobalSearchRecord ToProto(const GlobalSearchRecord& search);
proto::SlamPhaseTimes ToProto(const SlamPhaseTimes& times);

// A run between two scans or two epochs of a global search, in the form the coordinator stores
// to resume it after a restart.
proto::RssCheckpoint ToProto(const RssSlamState& state);
// Throws Error saying what does not hang together: pose columns of other lengths than next_scan,
// a loop or a global search over scans not done yet, a loop-triggered search with no loop.
RssSlamState RssSlamStateFromProto(const proto::RssCheckpoint& checkpoint);

// A global search task on the wire: the stretch, the poses and the loop.
proto::GlobalSearchSpec ToProto(const GlobalSearchTask& task);
// The task a spec describes; its poses point into `poses`, which it fills. Throws Error when the
// spec does not hang together (a stretch outside its poses, a loop outside the stretch).
GlobalSearchTask GlobalSearchTaskFromProto(const proto::GlobalSearchSpec& spec,
                                           std::vector<Pose2>& poses);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_RSS_RSS_PROTO_H_
