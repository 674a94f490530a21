#include "common/service/job_inputs.h"

#include <spdlog/spdlog.h>

#include "common/io/carmen_reader.h"
#include "common/io/relations.h"

namespace evoslam {

std::filesystem::path NeedDataset(const DatasetFiles& files, const proto::DatasetRef& ref,
                                  const char* what) {
  if (auto path = files.Find(ref)) return *path;
  throw Error(std::string(what) + " " + ref.name() + " (" + ref.sha256() + ") is not available");
}

Dataset LoadJobLog(const DatasetFiles& files, const proto::DatasetRef& log, bool lenient) {
  CarmenReadStats stats;
  Dataset dataset = NamedInput(log, [&] {
    return ReadCarmen(NeedDataset(files, log, "log"), {.lenient = lenient}, &stats);
  });
  if (stats.skipped > 0) {
    spdlog::warn("{}: skipped {} malformed lines (first: {})", log.name(), stats.skipped,
                 stats.first_skip_reason);
  }
  dataset.source = log.name();
  return dataset;
}

std::optional<NamedRelations> LoadJobRelations(const DatasetFiles& files,
                                               const proto::DatasetRef& relations) {
  if (relations.sha256().empty()) return std::nullopt;
  const std::filesystem::path path = NeedDataset(files, relations, "relations");
  return NamedRelations{relations.name(),
                        NamedInput(relations, [&] { return ReadRelations(path); })};
}

}  // namespace evoslam
