#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_KEY_POINTS_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_KEY_POINTS_H_

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "common/sensor/dataset.h"
#include "common/transform/pose2.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// One scan's gap (FindScanGaps) taken as evidence of a key point.
struct KeyPointSighting {
  std::size_t scan;       // index in dataset.scans
  std::size_t beam;       // the beam of the gap's near edge
  Eigen::Vector2d point;  // the gap's near edge, in that scan's laser frame
};

// A cell of the key point grid that enough sightings from distinct viewpoints agree on.
struct KeyPoint {
  Eigen::Vector2d position;  // world, the centre of its cell of the key point grid
  double belief;             // Dempster-Shafer: 1 - (1 - sighting_belief)^(independent sightings)
  // Every sighting that falls within one cell of it, in scan order (beam order within a scan):
  // the scans at which the robot sees it. Sightings from nearby viewpoints are listed though
  // only the first of them counts toward the belief.
  std::vector<KeyPointSighting> sightings;
};

// Throws evoslam::Error naming the first field (key_points.NAME) out of its range.
void ValidateKeyPointParams(const proto::KeyPointParams& params);

// The key points seen from the scans at these laser poses (one per scan of `dataset`, world
// frame, poses.size() <= scans; the scans beyond are not used), ordered by their first sighting
// (004 §2, eq. 4).
//
// Every gap of every scan is a sighting of the world point pose * near edge, which falls in a
// cell of a grid of cell_size_m anchored at the world origin. A cell gathers the sightings within
// one cell of it (eq. 4's tolerance for the poses' error). Each sighting is a simple support
// function of mass sighting_belief; Dempster's rule combines them into 1 - prod(1 - mass). Only
// sightings from a viewpoint at least min_view_shift_m from those already counted count: a robot
// that stands still, or turns on the spot, sees the same line of sight again and brings no new
// evidence. A cell whose belief reaches confirm_belief is a key point, unless a stronger one (more
// independent sightings, then more sightings, then more in the cell itself, then a centre nearer
// their mean) lies within two cells: their gathered sightings would overlap, so they are one point
// of the world.
//
// Throws evoslam::Error for invalid parameters, a max_range_m that is not positive and finite, or
// more poses than scans.
std::vector<KeyPoint> FindKeyPoints(const Dataset& dataset, std::span<const Pose2> laser_poses,
                                    const proto::KeyPointParams& params, double max_range_m);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_KEY_POINTS_H_
