#include "common/report/run_pictures.h"

#include <fmt/format.h>
#include <google/protobuf/util/json_util.h>

#include <utility>

#include "common/grid/map_io.h"
#include "common/io/file_bytes.h"
#include "common/line_map/line_map.h"
#include "common/util/error.h"
#include "evoslam/localize.pb.h"
#include "evoslam/slam.pb.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;

// The folder's file `name`, which holds `what`; throws Error when it is not there.
fs::path Need(const fs::path& dir, const char* name, const char* what) {
  fs::path path = dir / name;
  if (!fs::exists(path)) {
    throw Error(
        fmt::format("{} has no {} ({}), which its pictures need", dir.string(), name, what));
  }
  return path;
}

// The folder as given, without a trailing separator, to name a run in a legend.
std::string RunName(const fs::path& dir) {
  fs::path name = dir.lexically_normal();
  if (!name.has_filename()) name = name.parent_path();
  return name.string();
}

// The error in a title, and alone for a legend: the aligned RMS error against ground truth when
// known, else the relation error.
struct ErrorTexts {
  std::string title;
  std::string brief;
};

template <typename Report>
ErrorTexts Errors(const Report& r) {
  if (r.has_absolute_errors()) {
    const double cm = 100.0 * r.absolute_errors().aligned_rms_translation_m();
    return {fmt::format("aligned RMS error {:.2f} cm against ground truth", cm),
            fmt::format("{:.2f} cm aligned RMS", cm)};
  }
  if (r.has_relation_errors() && r.relation_errors().relations() > 0) {
    const auto& e = r.relation_errors();
    return {fmt::format("relation error {:.4f} +- {:.4f} m ({})", e.translation_mean_m(),
                        e.translation_std_m(), e.source()),
            fmt::format("{:.4f} m relation error", e.translation_mean_m())};
  }
  return {};
}

std::string Title(std::string what, const ErrorTexts& errors) {
  return errors.title.empty() ? what : what + " - " + errors.title;
}

std::vector<StampedPose> ReadTruthIfMeasured(const fs::path& dir, bool measured) {
  if (!measured) return {};
  return ReadTrajectory(Need(dir, "truth.txt", "the ground truth its errors are measured against"));
}

OccupancyGrid ReadGrid(const fs::path& dir) {
  const fs::path yaml = Need(dir, "map.yaml", "the map");
  Need(dir, "map.pgm", "the map's cells");
  return ReadMapYaml(yaml);
}

RunRecord ReadSlamRun(const fs::path& dir, const proto::SlamReport& report) {
  const auto& p = report.params();
  const ErrorTexts errors = Errors(report);
  std::vector<StampedPose> estimate =
      ReadTrajectory(Need(dir, "trajectory.txt", "the estimated poses"));
  std::vector<LoopLink> loops;
  for (const proto::LoopClosureRecord& loop : report.loops()) {
    if (loop.earlier() >= estimate.size() || loop.later() >= estimate.size()) {
      throw Error(fmt::format("{}: the loop from scan {} back to {} lies beyond the {} poses of {}",
                              (dir / "report.json").string(), loop.later(), loop.earlier(),
                              estimate.size(), (dir / "trajectory.txt").string()));
    }
    loops.push_back(
        {estimate[loop.earlier()].pose.translation(), estimate[loop.later()].pose.translation()});
  }
  return RunRecord{
      .dir = dir,
      .slam = true,
      .title = Title(fmt::format("{} - SLAM ({}), {} scans", p.log(), p.method(), report.scans()),
                     errors),
      .error = errors.brief,
      .map = MapModel(ReadGrid(dir)),
      .estimate = std::move(estimate),
      .odometry = ReadTrajectory(Need(dir, "odometry.txt", "the odometry at each scan")),
      .truth = ReadTruthIfMeasured(dir, report.has_absolute_errors()),
      .loops = std::move(loops)};
}

MapModel ReadLocalizationMap(const fs::path& dir) {
  if (fs::exists(dir / "map.yaml")) return MapModel(ReadGrid(dir));
  return MapModel(ReadLineMap(Need(dir, "map.lines", "the map it localized in")));
}

RunRecord ReadLocalizeRun(const fs::path& dir, const proto::LocalizeReport& report) {
  const auto& p = report.params();
  const ErrorTexts errors = Errors(report);
  return RunRecord{.dir = dir,
                   .slam = false,
                   .title = Title(fmt::format("{} - localization in {} ({}, {}), {} scans", p.log(),
                                              p.map(), p.optimizer(), p.fitness(), report.scans()),
                                  errors),
                   .error = errors.brief,
                   .map = ReadLocalizationMap(dir),
                   .estimate = ReadTrajectory(Need(dir, "trajectory.txt", "the estimated poses")),
                   .odometry = {},
                   .truth = ReadTruthIfMeasured(dir, report.has_absolute_errors()),
                   .loops = {}};
}

std::string Label(const RunRecord& run) {
  const std::string name = RunName(run.dir);
  return run.error.empty() ? name : name + " (" + run.error + ")";
}

}  // namespace

RunRecord ReadRun(const fs::path& dir) {
  if (!fs::is_directory(dir)) {
    throw Error(
        fmt::format("{} is not a folder: plot takes the folder a slam or localize run "
                    "wrote (its --out)",
                    dir.string()));
  }
  const fs::path path = Need(dir, "report.json", "what ran and how well");
  const std::string json = ReadFileBytes(path);
  proto::SlamReport slam;
  if (google::protobuf::util::JsonStringToMessage(json, &slam).ok() &&
      !slam.params().method().empty()) {
    return ReadSlamRun(dir, slam);
  }
  proto::LocalizeReport localize;
  const auto status = google::protobuf::util::JsonStringToMessage(json, &localize);
  if (!status.ok()) {
    throw InputError(path.string(), 0,
                     "neither a slam nor a localize report: " + status.ToString());
  }
  return ReadLocalizeRun(dir, localize);
}

MapPictureContent TrajectoryPicture(const RunRecord& run, const RunRecord* compared) {
  MapPictureContent content{
      .title = run.title, .layers = {}, .shows_loops = run.slam, .loops = run.loops};
  if (!run.odometry.empty()) {
    content.layers.push_back(MakeLayer(LayerKind::kOdometry, "odometry alone", run.odometry));
  }
  if (!run.truth.empty()) {
    content.layers.push_back(MakeLayer(LayerKind::kTruth, "ground truth", run.truth));
  }
  if (compared) {
    content.layers.push_back(MakeLayer(LayerKind::kCompared, Label(*compared), compared->estimate));
  }
  content.layers.push_back(
      MakeLayer(LayerKind::kEstimate, compared ? Label(run) : "estimate", run.estimate));
  return content;
}

std::vector<std::string> WriteRunPictures(const RunRecord& run, const fs::path& dir) {
  if (!run.slam) {
    WriteMapPicture(run.map, TrajectoryPicture(run), dir / "map.png");
    return {"map.png"};
  }
  WriteMapPicture(run.map, {.title = run.title, .layers = {}, .shows_loops = false, .loops = {}},
                  dir / "map.png");
  WriteMapPicture(run.map, TrajectoryPicture(run), dir / "map_trajectory.png");
  return {"map.png", "map_trajectory.png"};
}

}  // namespace evoslam
