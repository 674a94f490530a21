#include "common/report/localize_outputs.h"

#include <fstream>

#include "common/eval/trajectory_errors.h"
#include "common/grid/map_io.h"
#include "common/io/file_bytes.h"
#include "common/io/trajectory_io.h"
#include "common/report/localize_report.h"
#include "common/report/map_picture.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

proto::ResultFile ReadBack(const TempDir& dir, const std::string& name) {
  proto::ResultFile file;
  file.set_name(name);
  file.set_content(ReadFileBytes(dir / name));
  return file;
}

}  // namespace

std::vector<proto::ResultFile> LocalizeOutputs(const MapModel& map, const Dataset& dataset,
                                               const proto::LocalizeParams& params,
                                               const LocalizeResult& result,
                                               const std::optional<NamedRelations>& relations,
                                               std::uint32_t threads) {
  // The writers all write files; they write into a private folder and are read back.
  const TempDir dir("evoslam-outputs");
  std::vector<std::string> outputs;
  if (params.map_from_log() && map.grid()) {
    WriteMapYaml(*map.grid(), dir / "map.yaml");
    outputs.insert(outputs.end(), {"map.yaml", "map.pgm"});
  }
  WriteTrajectoryText(result.trajectory, dir / "trajectory.txt");
  WriteTrajectoryTum(result.trajectory, dir / "trajectory.tum");
  outputs.insert(outputs.end(), {"trajectory.txt", "trajectory.tum"});

  proto::LocalizeReport report;
  report.set_format_version(1);
  report.set_evoslam_version("0.1.0");
  *report.mutable_params() = params;
  report.set_scans(static_cast<std::uint32_t>(result.trajectory.size()));
  report.set_evaluations(result.evaluations);
  report.set_runtime_s(result.seconds);
  report.set_scans_per_second(result.seconds > 0 ? result.trajectory.size() / result.seconds : 0);
  report.set_threads(threads);
  double fitness_sum = 0.0;
  for (double f : result.fitness) fitness_sum += f;
  report.set_mean_fitness(result.fitness.empty() ? 0.0 : fitness_sum / result.fitness.size());

  std::vector<StampedPose> truth;
  for (std::size_t i = 0; i < result.trajectory.size(); ++i) {
    const LaserScan& s = dataset.scans[i];
    if (s.true_pose) truth.push_back({s.timestamp, *s.true_pose});
  }
  if (!truth.empty()) {
    *report.mutable_absolute_errors() = ToProto(ComputeAbsoluteErrors(result.trajectory, truth));
  }
  if (relations) {
    *report.mutable_relation_errors() =
        ToProto(ComputeRelationErrors(result.trajectory, relations->relations), relations->source);
  } else if (truth.size() > 1) {
    *report.mutable_relation_errors() =
        ToProto(ComputeRelationErrors(result.trajectory, RelationsFromTruth(truth)),
                "ground truth, consecutive scans");
  }

  std::vector<TrajectoryLayer> layers;
  if (!truth.empty()) {
    TrajectoryLayer t{"truth", {}, {0, 160, 0}};
    for (const auto& s : truth) t.poses.push_back(s.pose);
    layers.push_back(std::move(t));
  }
  TrajectoryLayer estimated{"estimate", {}, {220, 30, 30}};
  for (const auto& s : result.trajectory) estimated.poses.push_back(s.pose);
  layers.push_back(std::move(estimated));
  WriteMapPicture(map, layers, dir / "map.png");
  outputs.insert(outputs.end(), {"map.png", "report.json", "summary.txt"});
  for (const auto& o : outputs) report.add_outputs(o);

  WriteJson(report, dir / "report.json");
  std::ofstream(dir / "summary.txt") << FormatSummary(report);

  std::vector<proto::ResultFile> files;
  for (const auto& o : outputs) files.push_back(ReadBack(dir, o));
  return files;
}

}  // namespace evoslam
