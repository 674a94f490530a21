#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_TRAJECTORY_SEGMENTS_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_TRAJECTORY_SEGMENTS_H_

#include <cstddef>
#include <span>
#include <vector>

#include "common/transform/pose2.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// A stretch of the trajectory that one correction scales and bends (004 §3.2): the motion from
// scan `first` to scan `last`, which is the next segment's first.
struct TrajectorySegment {
  std::size_t first = 0;
  std::size_t last = 0;
  double length = 0.0;  // [d_j] the path travelled, m
  double turn = 0.0;    // [theta_j] the heading change, rad
};

// A segment's correction (004 eq. 9): its length becomes length + `length`, its turn turn + `turn`.
struct SegmentCorrection {
  double length = 0.0;  // [delta d_j], m
  double turn = 0.0;    // [delta theta_j], rad
};

// Throws Error naming the first field out of its range.
void ValidateTrajectorySegmentParams(const proto::TrajectorySegmentParams& params);

// Cuts the trajectory through `poses` (one per scan) into segments: each ends once it has travelled
// length_m or turned max_turn_rad, whichever comes first. A scan of `fine_scans` (sorted; scans
// that sight a key point) ends the segment before it and starts one that ends after
// key_point_length_m. Every segment spans at least one step; the last may be shorter. Fewer than
// two poses: none.
std::vector<TrajectorySegment> CutSegments(std::span<const Pose2> poses,
                                           std::span<const std::size_t> fine_scans,
                                           const proto::TrajectorySegmentParams& params);

// The trajectory as steps between scans grouped into segments, for rebuilding its poses under a
// correction of each segment. A correction stretches every step of its segment's translation by
// (length + delta d) / length and adds delta theta to the segment's heading, spread over its steps
// in proportion to the distance each travels (evenly over the steps of a segment that does not
// move): odometry's heading error grows with the distance driven. A segment that does not move
// keeps its translation, whatever its length correction.
class SegmentedTrajectory {
 public:
  SegmentedTrajectory(std::span<const Pose2> poses, std::vector<TrajectorySegment> segments);

  const std::vector<TrajectorySegment>& segments() const { return segments_; }
  std::size_t scans() const { return steps_.size() + 1; }
  const Pose2& start() const { return start_; }

  // The poses of scans segments()[first].first to segments()[first + corrections.size() -
  // 1].last, both included, with each of those segments corrected, starting from `from`: the
  // corrected pose of segments()[first].first. `out` takes one pose per scan of that range.
  void Poses(std::size_t first, std::span<const SegmentCorrection> corrections, const Pose2& from,
             std::span<Pose2> out) const;
  // Every scan's pose under a correction of every segment, from start().
  std::vector<Pose2> AllPoses(std::span<const SegmentCorrection> corrections) const;

 private:
  Pose2 start_;
  std::vector<Pose2> steps_;  // steps_[k]: from scan k to scan k + 1, in scan k's frame
  // The share of its segment's heading correction each step takes.
  std::vector<double> turn_share_;
  std::vector<TrajectorySegment> segments_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_TRAJECTORY_SEGMENTS_H_
