#include "common/service/job_inputs.h"

#include <spdlog/spdlog.h>

#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

#include "common/eval/trajectory_errors.h"
#include "common/grid/map_io.h"
#include "common/io/carmen_reader.h"
#include "common/io/relations.h"
#include "common/report/slam_report.h"
#include "common/util/counted.h"

namespace evoslam {

bool IsMapYaml(const proto::DatasetRef& map) {
  const std::string ext = std::filesystem::path(SafeFileName(map.name())).extension().string();
  return ext == ".yaml" || ext == ".yml";
}

void CheckMapImageIsOwn(const std::string& yaml, const proto::DatasetRef& map,
                        const proto::DatasetRef& image) {
  if (image.sha256().empty()) {
    throw Error("map " + map.name() + ": a map_server map needs its image uploaded with it");
  }
  std::istringstream in(yaml);
  const std::string named = ReadMapYamlImageName(in, map.name());
  const std::string own = SafeFileName(image.name());
  if (named != own) {
    throw Error("map " + map.name() + ": its image must be the one uploaded with the job, named '" +
                own + "' alone; '" + named.substr(0, 200) +
                "' is not (a job's files may refer only to one another)");
  }
}

std::filesystem::path NeedDataset(const DatasetFiles& files, const proto::DatasetRef& ref,
                                  const char* what) {
  if (auto path = files.Find(ref)) return *path;
  throw Error(std::string(what) + " " + ref.name() + " (" + ref.sha256() + ") is not available");
}

Dataset LoadJobLog(const DatasetFiles& files, const proto::DatasetRef& log, bool lenient) {
  CarmenReadStats stats;
  const std::filesystem::path path = NeedDataset(files, log, "log");
  Dataset dataset = NamedInput({{path, log.name()}},
                               [&] { return ReadCarmen(path, {.lenient = lenient}, &stats); });
  if (stats.skipped > 0) {
    spdlog::warn("{}: skipped {} (the first, line {}: {})", log.name(),
                 Counted(stats.skipped, "malformed line"), stats.first_skip_line,
                 stats.first_skip_reason);
  }
  dataset.source = log.name();
  return dataset;
}

std::shared_ptr<const Dataset> LoadSharedJobLog(const DatasetFiles& files,
                                                const proto::DatasetRef& log, bool lenient) {
  // Each log's slot has its own lock, so that a second load waits for the first one's parse
  // while loads of other logs go on.
  struct Slot {
    std::mutex mutex;
    std::weak_ptr<const Dataset> dataset;
  };
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<Slot>> slots;
  const std::string key = log.sha256() + "/" + log.name() + (lenient ? "/lenient" : "");
  std::shared_ptr<Slot> slot;
  {
    const std::lock_guard lock(mutex);
    std::erase_if(slots, [](const auto& entry) {
      return entry.second.use_count() == 1 && entry.second->dataset.expired();
    });
    std::shared_ptr<Slot>& found = slots[key];
    if (!found) found = std::make_shared<Slot>();
    slot = found;
  }
  const std::lock_guard lock(slot->mutex);
  if (std::shared_ptr<const Dataset> held = slot->dataset.lock()) return held;
  auto dataset = std::make_shared<const Dataset>(LoadJobLog(files, log, lenient));
  slot->dataset = dataset;
  return dataset;
}

std::optional<NamedRelations> LoadJobRelations(const DatasetFiles& files,
                                               const proto::DatasetRef& relations,
                                               const Dataset& log) {
  if (relations.sha256().empty()) return std::nullopt;
  const std::filesystem::path path = NeedDataset(files, relations, "relations");
  NamedRelations named{relations.name(),
                       NamedInput({{path, relations.name()}}, [&] { return ReadRelations(path); })};
  if (ComputeRelationErrors(ScanOdometry(log, log.scans.size()), named.relations).relations == 0) {
    throw InputError(named.source, 0,
                     "none of its " + std::to_string(named.relations.size()) +
                         " relations joins two scans of " + log.source +
                         " (matched by timestamp); are they another log's?");
  }
  return named;
}

}  // namespace evoslam
