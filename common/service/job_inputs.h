#ifndef EVOSLAM_COMMON_SERVICE_JOB_INPUTS_H_
#define EVOSLAM_COMMON_SERVICE_JOB_INPUTS_H_

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>

#include "common/report/localize_report.h"
#include "common/sensor/dataset.h"
#include "common/service/dataset_files.h"
#include "common/util/error.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Whether a job's map is a map_server YAML, read with the image uploaded beside it.
bool IsMapYaml(const proto::DatasetRef& map);

// A job's files may refer only to one another: a map_server YAML (`yaml`, its bytes) must name
// as its image the image uploaded with the job (`image`), by that file name alone. A path there
// would make every host that runs the job read a file of its own disk. Throws Error otherwise,
// having read no other file, so that the message tells nothing about what exists anywhere.
void CheckMapImageIsOwn(const std::string& yaml, const proto::DatasetRef& map,
                        const proto::DatasetRef& image);

// Where `ref` is kept; throws Error naming it (`what`: "log", "map", ...) when it is not here.
std::filesystem::path NeedDataset(const DatasetFiles& files, const proto::DatasetRef& ref,
                                  const char* what);

// A job's input file as this host reads it (`path`, in the dataset cache) and as whoever
// submitted the job named it.
struct CachedInput {
  std::filesystem::path path;
  std::string name;
};

// Runs `read`, naming a bad input by the name it was uploaded under instead of the cache path
// it is read from, which means nothing to whoever submitted the job. Of an input read together
// with others (a map's YAML and its image), the one at fault is named.
template <typename Read>
auto NamedInput(std::initializer_list<CachedInput> inputs, Read read) {
  try {
    return read();
  } catch (const InputError& e) {
    const std::filesystem::path source = std::filesystem::path(e.source()).lexically_normal();
    for (const CachedInput& input : inputs) {
      if (source == input.path.lexically_normal()) {
        throw InputError(input.name, e.line(), e.message());
      }
    }
    throw;
  }
}

// A job's CARMEN log, parsed; with `lenient`, malformed lines are skipped and the skips logged.
// Its source is the name it was uploaded under. Throws Error (InputError for a bad line) naming
// the log that way.
Dataset LoadJobLog(const DatasetFiles& files, const proto::DatasetRef& log, bool lenient);

// LoadJobLog's Dataset, parsed once per process: while anyone holds it, a load of the same log
// (the same bytes under the same name, as lenient) returns it instead of parsing another copy.
// A coordinator and its workers in one process (the command's embedded service) share it so.
std::shared_ptr<const Dataset> LoadSharedJobLog(const DatasetFiles& files,
                                                const proto::DatasetRef& log, bool lenient);

// The relations a job's trajectory is scored against; nullopt when the job names none. Throws
// InputError naming the relations when none of them joins two of `log`'s scans (another log's
// relations would otherwise score nothing and report an error of zero).
std::optional<NamedRelations> LoadJobRelations(const DatasetFiles& files,
                                               const proto::DatasetRef& relations,
                                               const Dataset& log);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_JOB_INPUTS_H_
