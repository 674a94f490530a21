#include "common/report/slam_outputs.h"

#include <spdlog/spdlog.h>

#include <span>
#include <string>

#include "common/grid/grid_image.h"
#include "common/grid/map_io.h"
#include "common/grid/occupancy_grid.h"
#include "common/io/file_bytes.h"
#include "common/io/trajectory_io.h"
#include "common/report/map_picture.h"
#include "common/report/result_files.h"
#include "common/report/slam_report.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

// Room around the scans' extent, as for a grid built from a log for localization, so that the
// outermost returns' cells do not touch the map's edge.
constexpr double kMapMargin = 1.0;

// MakeSlamReport has checked that the poses do not outnumber the scans.
void CheckResult(const RssSlamResult& result) {
  const std::size_t n = result.trajectory.size();
  if (n == 0) throw Error("SLAM outputs: the result has no poses");
  for (const LoopClosure& loop : result.loops) {
    if (loop.constraint.earlier >= n || loop.constraint.later >= n) {
      throw Error("SLAM outputs: the loop between scans " +
                  std::to_string(loop.constraint.earlier) + " and " +
                  std::to_string(loop.constraint.later) + " lies beyond the " + std::to_string(n) +
                  " poses");
    }
  }
}

// The map at `resolution`, or as much coarser as it takes to fit: the search's map has room for
// more cells than an output map, and a run must not be lost for want of a fine picture of it.
OccupancyGrid GridAtPoses(const Dataset& dataset, std::span<const StampedPose> trajectory,
                          double resolution) {
  std::vector<Pose2> poses;
  poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) poses.push_back(p.pose);
  const std::span<const LaserScan> scans = std::span(dataset.scans).first(poses.size());
  const double fitting = OccupancyGrid::FittingResolution(scans, poses, resolution, kMapMargin);
  if (fitting != resolution) {
    spdlog::warn(
        "the map of the run does not fit in {} cells at {} m per cell; it is written at {} m",
        OccupancyGrid::kMaxCells, resolution, fitting);
  }
  return OccupancyGrid::FromScans(scans, poses, fitting, kMapMargin);
}

// Drawn from the least telling up, so that the estimate hides odometry and truth where they
// coincide, and the loops go over everything.
void WriteMapTrajectory(OccupancyGrid grid, const Dataset& dataset, const RssSlamResult& result,
                        const std::filesystem::path& path) {
  const std::size_t n = result.trajectory.size();
  const std::vector<StampedPose> truth = ScanTruth(dataset, n);
  std::vector<TrajectoryLayer> layers;
  layers.push_back(MakeLayer("odometry", ScanOdometry(dataset, n), kOdometryColor));
  if (!truth.empty()) layers.push_back(MakeLayer("truth", truth, kTruthColor));
  layers.push_back(MakeLayer("estimate", result.trajectory, kEstimateColor));
  WorldCanvas canvas = DrawMapPicture(MapModel(std::move(grid)), layers);
  for (const LoopClosure& loop : result.loops) {
    const Eigen::Vector2d a = result.trajectory[loop.constraint.earlier].pose.translation();
    const Eigen::Vector2d b = result.trajectory[loop.constraint.later].pose.translation();
    canvas.DrawSegment(a, b, kLoopColor, 2);
    canvas.DrawPoint(a, 4.0, kLoopColor);
    canvas.DrawPoint(b, 4.0, kLoopColor);
  }
  WritePng(canvas.image(), path);
}

}  // namespace

std::vector<proto::ResultFile> SlamOutputs(const Dataset& dataset, const proto::SlamParams& params,
                                           const RssSlamResult& result,
                                           const std::optional<NamedRelations>& relations,
                                           std::uint32_t threads) {
  proto::SlamReport report = MakeSlamReport(dataset, params, result, relations, threads);
  CheckResult(result);
  // The writers all write files; they write into a private folder and are read back.
  const TempDir dir("evoslam-outputs");
  WriteTrajectoryText(result.trajectory, dir / "trajectory.txt");
  WriteTrajectoryTum(result.trajectory, dir / "trajectory.tum");
  OccupancyGrid grid = GridAtPoses(dataset, result.trajectory, params.rss().map().cell_size_m());
  report.set_map_resolution_m(grid.resolution());
  WriteMapYaml(grid, dir / "map.yaml");
  WriteGridPng(grid, dir / "map.png");
  WriteMapTrajectory(std::move(grid), dataset, result, dir / "map_trajectory.png");

  const std::vector<std::string> outputs = {
      "trajectory.txt", "trajectory.tum",     "map.yaml",    "map.pgm",
      "map.png",        "map_trajectory.png", "report.json", "summary.txt"};
  for (const std::string& o : outputs) report.add_outputs(o);
  WriteJson(report, dir / "report.json");
  WriteFileBytes(dir / "summary.txt", FormatSlamSummary(report));
  return ReadResultFiles(dir.path(), outputs);
}

}  // namespace evoslam
