#ifndef EVOSLAM_COMMON_REPORT_RESULT_FILES_H_
#define EVOSLAM_COMMON_REPORT_RESULT_FILES_H_

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "evoslam/service.pb.h"

namespace evoslam {

// The named files of a folder as a job's result files, in the order named: the outputs' writers
// write files, and a job hands back their bytes. Throws InputError naming a file it cannot read.
std::vector<proto::ResultFile> ReadResultFiles(const std::filesystem::path& dir,
                                               std::span<const std::string> names);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_RESULT_FILES_H_
