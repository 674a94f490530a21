#include "common/report/localize_outputs.h"

#include "common/eval/trajectory_errors.h"
#include "common/grid/map_io.h"
#include "common/io/file_bytes.h"
#include "common/io/trajectory_io.h"
#include "common/line_map/line_map.h"
#include "common/report/result_files.h"
#include "common/report/run_pictures.h"
#include "common/util/temp_dir.h"

namespace evoslam {

std::vector<proto::ResultFile> LocalizeOutputs(const MapModel& map, const Dataset& dataset,
                                               const proto::LocalizeParams& params,
                                               const LocalizeResult& result,
                                               const std::optional<NamedRelations>& relations,
                                               std::uint32_t threads) {
  // The writers all write files; they write into a private folder and are read back.
  const TempDir dir("evoslam-outputs");
  std::vector<std::string> outputs;
  if (const OccupancyGrid* grid = map.grid()) {
    WriteMapYaml(*grid, dir / "map.yaml");
    outputs.insert(outputs.end(), {"map.yaml", "map.pgm"});
  } else if (const LineMap* walls = map.walls()) {
    WriteLineMap(*walls, dir / "map.lines");
    outputs.push_back("map.lines");
  }
  WriteTrajectoryText(result.trajectory, dir / "trajectory.txt");
  WriteTrajectoryTum(result.trajectory, dir / "trajectory.tum");
  outputs.insert(outputs.end(), {"trajectory.txt", "trajectory.tum"});
  const std::vector<StampedPose> truth = ScanTruth(dataset, result.trajectory.size());
  if (!truth.empty()) {
    WriteTrajectoryText(truth, dir / "truth.txt");
    outputs.push_back("truth.txt");
  }

  proto::LocalizeReport report;
  report.set_format_version(1);
  report.set_evoslam_version(kEvoslamVersion);
  *report.mutable_params() = params;
  report.set_scans(static_cast<std::uint32_t>(result.trajectory.size()));
  report.set_evaluations(result.evaluations);
  report.set_runtime_s(result.seconds);
  report.set_scans_per_second(result.seconds > 0 ? result.trajectory.size() / result.seconds : 0);
  report.set_threads(threads);
  double fitness_sum = 0.0;
  for (double f : result.fitness) fitness_sum += f;
  report.set_mean_fitness(result.fitness.empty() ? 0.0 : fitness_sum / result.fitness.size());
  for (const OdometryStall& stall : result.odometry_stalls) {
    *report.add_odometry_stalls() = ToProto(stall);
  }
  if (auto warnings = LogWarningsOf(dataset, result.trajectory.size())) {
    *report.mutable_log_warnings() = *warnings;
  }

  if (!truth.empty()) {
    *report.mutable_absolute_errors() = ToProto(ComputeAbsoluteErrors(result.trajectory, truth));
  }
  if (auto errors = RelationErrorsReport(result.trajectory, truth, relations)) {
    *report.mutable_relation_errors() = std::move(*errors);
  }

  outputs.insert(outputs.end(), {"map.png", "report.json", "summary.txt"});
  for (const auto& o : outputs) report.add_outputs(o);

  WriteJson(report, dir / "report.json");
  WriteFileBytes(dir / "summary.txt", FormatSummary(report));
  // Drawn from the files, as `evoslam plot` draws them.
  WriteRunPictures(ReadRun(dir.path()), dir.path());
  return ReadResultFiles(dir.path(), outputs);
}

}  // namespace evoslam
