#ifndef EVOSLAM_COMMON_SERVICE_SLAM_CHECKPOINT_H_
#define EVOSLAM_COMMON_SERVICE_SLAM_CHECKPOINT_H_

#include "common/slam/rss_slam.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// A SLAM run between two scans or two epochs of a global search, in the form the coordinator
// stores to resume it after a restart.
proto::SlamCheckpoint ToProto(const RssSlamState& state);
// Throws Error saying what does not hang together: pose columns of other lengths than next_scan,
// a loop or a global search over scans not done yet, a loop-triggered search with no loop.
RssSlamState RssSlamStateFromProto(const proto::SlamCheckpoint& checkpoint);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_SLAM_CHECKPOINT_H_
