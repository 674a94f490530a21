#ifndef EVOSLAM_COMMON_SERVICE_JOB_INPUTS_H_
#define EVOSLAM_COMMON_SERVICE_JOB_INPUTS_H_

#include <filesystem>
#include <optional>
#include <string>

#include "common/report/localize_report.h"
#include "common/sensor/dataset.h"
#include "common/service/dataset_files.h"
#include "common/util/error.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Where `ref` is kept; throws Error naming it (`what`: "log", "map", ...) when it is not here.
std::filesystem::path NeedDataset(const DatasetFiles& files, const proto::DatasetRef& ref,
                                  const char* what);

// Runs `read`, naming a bad input by the name it was uploaded under instead of the cache path
// it is read from, which means nothing to whoever submitted the job.
template <typename Read>
auto NamedInput(const proto::DatasetRef& ref, Read read) {
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

// A job's CARMEN log, parsed; with `lenient`, malformed lines are skipped and the skips logged.
// Its source is the name it was uploaded under. Throws Error (InputError for a bad line) naming
// the log that way.
Dataset LoadJobLog(const DatasetFiles& files, const proto::DatasetRef& log, bool lenient);

// The relations a job's trajectory is scored against; nullopt when the job names none. Throws
// InputError naming the relations when none of them joins two of `log`'s scans (another log's
// relations would otherwise score nothing and report an error of zero).
std::optional<NamedRelations> LoadJobRelations(const DatasetFiles& files,
                                               const proto::DatasetRef& relations,
                                               const Dataset& log);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_JOB_INPUTS_H_
