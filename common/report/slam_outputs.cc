#include "common/report/slam_outputs.h"

#include <string>

#include "common/grid/map_io.h"
#include "common/io/file_bytes.h"
#include "common/io/trajectory_io.h"
#include "common/report/pareto_csv.h"
#include "common/report/pareto_fronts.h"
#include "common/report/pareto_picture.h"
#include "common/report/result_files.h"
#include "common/report/run_pictures.h"
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
  if (!result.pareto_fronts.empty()) CheckParetoFronts(result.pareto_fronts);
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
  const std::size_t n = result.trajectory.size();
  WriteTrajectoryText(result.trajectory, dir / "trajectory.txt");
  WriteTrajectoryTum(result.trajectory, dir / "trajectory.tum");
  WriteTrajectoryText(ScanOdometry(dataset, n), dir / "odometry.txt");
  std::vector<std::string> outputs = {"trajectory.txt", "trajectory.tum", "odometry.txt"};
  if (const std::vector<StampedPose> truth = ScanTruth(dataset, n); !truth.empty()) {
    WriteTrajectoryText(truth, dir / "truth.txt");
    outputs.push_back("truth.txt");
  }
  report.set_map_resolution_m(result.map.resolution());
  WriteMapYaml(result.map, dir / "map.yaml");
  outputs.insert(outputs.end(), {"map.yaml", "map.pgm", "map.png", "map_trajectory.png"});
  const std::span<const ParetoFront> fronts = result.pareto_fronts;
  if (!fronts.empty()) {
    WriteFileBytes(dir / "pareto.csv", ParetoCsv(fronts));
    outputs.insert(outputs.end(), {"pareto.csv", "pareto.png"});
  }
  outputs.insert(outputs.end(), {"report.json", "summary.txt"});
  for (const std::string& o : outputs) report.add_outputs(o);
  WriteJson(report, dir / "report.json");
  WriteFileBytes(dir / "summary.txt", FormatSlamSummary(report));
  // The map pictures drawn from the files, as `evoslam plot` draws them; the fronts under the
  // same title.
  const RunRecord run = ReadRun(dir.path());
  WriteRunPictures(run, dir.path());
  if (!fronts.empty()) WriteParetoPicture(fronts, run.title, dir / "pareto.png");
  return ReadResultFiles(dir.path(), outputs);
}

}  // namespace evoslam
