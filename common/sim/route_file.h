#ifndef EVOSLAM_COMMON_SIM_ROUTE_FILE_H_
#define EVOSLAM_COMMON_SIM_ROUTE_FILE_H_

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace evoslam {

// A route file: one waypoint per line, "x y" in metres in the world frame; '#' starts a comment
// and blank lines are ignored, as in line map files. The robot starts at the first waypoint.
// Plain, gzip or bzip2 text. Throws InputError naming the file and line for a missing file, a
// malformed line or a route of fewer than two waypoints.
std::vector<Eigen::Vector2d> ReadRoute(const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_ROUTE_FILE_H_
