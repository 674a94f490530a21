#include "common/slam/slam_method.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <vector>

namespace evoslam {
namespace {

// Room around the scans' extent, as for a grid built from a log for localization, so that the
// outermost returns' cells do not touch the map's edge.
constexpr double kMapMargin = 1.0;

}  // namespace

std::size_t ScansToMap(const Dataset& dataset, const proto::SlamParams& params) {
  const std::size_t n = dataset.scans.size();
  return params.max_scans() > 0 ? std::min<std::size_t>(n, params.max_scans()) : n;
}

OccupancyGrid OccupancyGridAtPoses(const Dataset& dataset, std::span<const StampedPose> trajectory,
                                   double cell_size) {
  std::vector<Pose2> poses;
  poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) poses.push_back(p.pose);
  const std::span<const LaserScan> scans = std::span(dataset.scans).first(poses.size());
  const double fitting = OccupancyGrid::FittingResolution(scans, poses, cell_size, kMapMargin);
  if (fitting != cell_size) {
    spdlog::warn(
        "the map of the run does not fit in {} cells at {} m per cell; it is written at {} m",
        OccupancyGrid::kMaxCells, cell_size, fitting);
  }
  return OccupancyGrid::FromScans(scans, poses, fitting, kMapMargin);
}

}  // namespace evoslam
