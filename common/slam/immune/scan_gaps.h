#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_SCAN_GAPS_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_SCAN_GAPS_H_

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "common/sensor/laser_scan.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// A large gap in one scan at the near edge of a depth discontinuity: where a section of the scan
// ends and the beam beyond it sees something farther. Such an edge is the silhouette of a convex
// corner, a fixed point of the world, whereas the gap's far side (the boundary of the corner's
// shadow) moves with the viewpoint.
struct ScanGap {
  std::size_t beam;       // the beam of the near edge
  Eigen::Vector2d point;  // the near edge, in the laser frame
  double width_m;         // the gap's width: from the near edge to the next kept section
};

// The key point candidates of one scan (004 §2, eqs. 5-8), in beam order.
//
// Beams fall into three kinds. A return nearer than max_range_m is a surface point. A beam that
// sees nothing within max_range_m (a return at or beyond it, or no return at the sensor's
// range_max) stands, as in 004's truncation of ranges, for a point at max_range_m on the beam
// (at range_max if that is nearer): the nearest place its surface can be. Any other reading (NaN,
// at or below range_min) tells nothing and ends a section without a gap.
//
// Successive points form a section while eq. 6 holds; sections of fewer than min_section_points
// beams are dropped. The surface point at an end of a kept section is a near edge when the
// neighbouring beam beyond that end is farther; the gap runs from it to the facing end of the
// next kept section that way, across dropped sections but no uninformative reading, and counts
// when wider than min_gap_m (eq. 8). Since a point at max range lies at the nearest place the
// unseen surface can be, a gap against it is never wider than the real one: a wall that merely
// runs out of range gives no gap, an obstacle's edge seen against open space does.
std::vector<ScanGap> FindScanGaps(const LaserScan& scan, const proto::KeyPointParams& params,
                                  double max_range_m);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_SCAN_GAPS_H_
