#ifndef EVOSLAM_COMMON_SIM_TRAJECTORY_H_
#define EVOSLAM_COMMON_SIM_TRAJECTORY_H_

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "common/line_map/line_map.h"
#include "common/sim/world.h"
#include "common/transform/pose2.h"

namespace evoslam {

struct PathOptions {
  double step = kDefaultScanSpacing;  // metres travelled between poses
  // Corners are rounded with circular arcs of this radius, smaller where the legs are too
  // short for it (down to turning on the spot for a reversal).
  double turn_radius = kMinWallClearance;
  // Turning is sampled as if along an arc of at least this radius, so that a tight turn or a
  // turn on the spot is spread over several poses (at most step / this radians apart).
  double min_turn_sampling_radius = 0.3;
};

// Poses along the route through the waypoints with rounded corners, heading along the path,
// evenly spaced by about options.step from the first waypoint to the last (both included).
// Consecutive duplicate waypoints are ignored. Throws Error for fewer than two distinct
// waypoints, non-finite waypoints or options that are not positive.
std::vector<Pose2> SmoothPath(std::span<const Eigen::Vector2d> waypoints,
                              const PathOptions& options = {});

// The closest approach of the path (the polyline through the poses' positions) to a wall.
struct PathClearance {
  double distance = 0.0;  // metres; `limit` when no wall comes closer
  std::size_t pose = 0;   // index of the pose that starts the closest piece of the path
};
PathClearance MeasureClearance(const LineMap& map, std::span<const Pose2> path, double limit);

// Length of the polyline through the poses' positions.
double PathLength(std::span<const Pose2> path);

// The world's route as SmoothPath poses about `step` metres apart; throws Error naming the
// world and the place when the path comes closer than kMinWallClearance to a wall.
std::vector<Pose2> RouteTrajectory(const World& world, double step);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_TRAJECTORY_H_
