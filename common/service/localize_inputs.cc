#include "common/service/localize_inputs.h"

#include <spdlog/spdlog.h>

#include "common/io/carmen_reader.h"
#include "common/localization/localize_params.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

std::filesystem::path Need(const DatasetFiles& files, const proto::DatasetRef& ref,
                           const char* what) {
  if (auto path = files.Find(ref)) return *path;
  throw Error(std::string(what) + " " + ref.name() + " (" + ref.sha256() + ") is not available");
}

// Runs `read`, naming a bad input by the name it was uploaded under instead of the cache path
// it is read from, which means nothing to whoever submitted the job.
template <typename Read>
auto Named(const proto::DatasetRef& ref, Read read) {
  try {
    return read();
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string prefix =
        e.source() + (e.line() > 0 ? ":" + std::to_string(e.line()) : std::string()) + ": ";
    throw InputError(ref.name(), e.line(),
                     what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
  }
}

}  // namespace

OccupancyGrid GridFromLog(const std::filesystem::path& path, double resolution, bool lenient) {
  if (!(resolution > 0.0)) throw Error("grid resolution must be positive");
  const Dataset dataset = ReadCarmen(path, {.lenient = lenient});
  std::vector<Pose2> poses;
  for (const LaserScan& s : dataset.scans) poses.push_back(s.true_pose.value_or(s.pose));
  spdlog::info("building a {:.3f} m grid from {} scans of {}", resolution, poses.size(),
               path.string());
  return OccupancyGrid::FromScans(dataset.scans, poses, resolution, 1.0);
}

std::shared_ptr<const LocalizeInputs> LoadLocalizeInputs(DatasetFiles& files,
                                                         const proto::DatasetRef& log,
                                                         const proto::DatasetRef& map,
                                                         const proto::DatasetRef& map_image,
                                                         const proto::LocalizeParams& params) {
  LocalizeOptions options = LocalizeOptionsFromProto(params);
  CarmenReadStats stats;
  Dataset dataset = Named(log, [&] {
    return ReadCarmen(Need(files, log, "log"), {.lenient = params.lenient()}, &stats);
  });
  if (stats.skipped > 0) {
    spdlog::warn("{}: skipped {} malformed lines (first: {})", log.name(), stats.skipped,
                 stats.first_skip_reason);
  }
  std::filesystem::path map_path = Need(files, map, "map");
  if (params.map_from_log()) {
    return std::make_shared<const LocalizeInputs>(LocalizeInputs{
        std::move(options), std::move(dataset), Named(map, [&] {
          return MapModel(GridFromLog(map_path, params.grid_resolution_m(), params.lenient()));
        })});
  }
  if (!map_image.sha256().empty()) map_path = files.MapWithImage(map, map_image);
  return std::make_shared<const LocalizeInputs>(LocalizeInputs{
      std::move(options), std::move(dataset), Named(map, [&] { return LoadMapModel(map_path); })});
}

}  // namespace evoslam
