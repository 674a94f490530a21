#include "common/service/localize_inputs.h"

#include <spdlog/spdlog.h>

#include "common/io/carmen_reader.h"
#include "common/io/file_bytes.h"
#include "common/localization/localize_params.h"
#include "common/service/job_inputs.h"
#include "common/util/error.h"

namespace evoslam {

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
  Dataset dataset = LoadJobLog(files, log, params.lenient());
  std::filesystem::path map_path = NeedDataset(files, map, "map");
  if (params.map_from_log()) {
    return std::make_shared<const LocalizeInputs>(LocalizeInputs{
        std::move(options), std::move(dataset), NamedInput({{map_path, map.name()}}, [&] {
          return MapModel(GridFromLog(map_path, params.grid_resolution_m(), params.lenient()));
        })});
  }
  std::filesystem::path image_path;
  if (IsMapYaml(map)) {
    // Checked again here, not only when the job was submitted: this host reads no file the
    // job's own files do not name.
    CheckMapImageIsOwn(ReadFileBytes(map_path), map, map_image);
    map_path = files.MapWithImage(map, map_image);
    image_path = map_path.parent_path() / NeedDataset(files, map_image, "map image").filename();
  }
  return std::make_shared<const LocalizeInputs>(
      LocalizeInputs{std::move(options), std::move(dataset),
                     NamedInput({{map_path, map.name()}, {image_path, map_image.name()}},
                                [&] { return LoadMapModel(map_path); })});
}

}  // namespace evoslam
