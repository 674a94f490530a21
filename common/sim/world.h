#ifndef EVOSLAM_COMMON_SIM_WORLD_H_
#define EVOSLAM_COMMON_SIM_WORLD_H_

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "common/line_map/line_map.h"

namespace evoslam {

// How close a simulated robot's route may come to a wall (its centre, metres).
inline constexpr double kMinWallClearance = 0.5;

// Travel between scans when a world does not say otherwise: the s-shaped corridor experiment's
// 219 scans over about 11.6 m.
inline constexpr double kDefaultScanSpacing = 0.053;

// A simulated environment: its walls and the route the robot drives through it.
struct World {
  std::string name;
  LineMap map;
  std::vector<Eigen::Vector2d> waypoints;  // the route; the robot starts at the first
  // Metres travelled between scans, so that the route gives about as many scans as the
  // experiment the world imitates logged.
  double scan_spacing = kDefaultScanSpacing;
};

// The built-in worlds (geometry invented after the experiments' descriptions):
//   "office-boxes"    10 x 10 m office with 40 x 60 cm cardboard boxes, 60 walls, ~30 m route.
//   "s-corridor"      s-shaped corridor in a 6 x 7.8 m footprint, ~11.6 m route.
//   "static-objects"  8 x 6.2 m room with many boxes scattered in it, ~29 m route.
//   "empty-room"      empty 8 x 6 m room, ~23 m route.
//   "office-cluster"  25.6 x 18.8 m: ten furnished offices on one hallway, 328 walls, a route of
//                     ~235 m through every office and back along the hallway.
// Throws Error listing the names for an unknown name.
World BuiltinWorld(std::string_view name);
std::vector<std::string> BuiltinWorldNames();

// A world from any line map. With no waypoints the route is a loop around the free space: the
// outline of the largest area enclosed by the walls whose points (on a 0.1 m lattice) keep
// 0.6 m from every wall, simplified to straight legs that keep kMinWallClearance (0.5 m). It
// follows the walls at about 0.6 m, enters every room whose doorway is wide enough (1.2 m plus)
// and passes around objects standing near walls, but not around free-standing ones in the
// middle of a room. Throws Error when the map is empty, a waypoint is not finite or there is no
// such area (give waypoints then).
World WorldFromLineMap(LineMap map, std::string name = "custom",
                       std::vector<Eigen::Vector2d> waypoints = {});

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_WORLD_H_
