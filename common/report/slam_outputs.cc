#include "common/report/slam_outputs.h"

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

// MakeSlamReport has checked that the poses do not outnumber the scans.
void CheckResult(const SlamResult& result) {
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

// Drawn from the least telling up, so that the estimate hides odometry and truth where they
// coincide, and the loops go over everything.
void WriteMapTrajectory(OccupancyGrid grid, const Dataset& dataset, const SlamResult& result,
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
                                           const SlamResult& result,
                                           const std::optional<NamedRelations>& relations,
                                           std::uint32_t threads) {
  proto::SlamReport report = MakeSlamReport(dataset, params, result, relations, threads);
  CheckResult(result);
  // The writers all write files; they write into a private folder and are read back.
  const TempDir dir("evoslam-outputs");
  WriteTrajectoryText(result.trajectory, dir / "trajectory.txt");
  WriteTrajectoryTum(result.trajectory, dir / "trajectory.tum");
  report.set_map_resolution_m(result.map.resolution());
  WriteMapYaml(result.map, dir / "map.yaml");
  WriteGridPng(result.map, dir / "map.png");
  WriteMapTrajectory(result.map, dataset, result, dir / "map_trajectory.png");

  const std::vector<std::string> outputs = {
      "trajectory.txt", "trajectory.tum",     "map.yaml",    "map.pgm",
      "map.png",        "map_trajectory.png", "report.json", "summary.txt"};
  for (const std::string& o : outputs) report.add_outputs(o);
  WriteJson(report, dir / "report.json");
  WriteFileBytes(dir / "summary.txt", FormatSlamSummary(report));
  return ReadResultFiles(dir.path(), outputs);
}

}  // namespace evoslam
