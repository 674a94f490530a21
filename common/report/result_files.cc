#include "common/report/result_files.h"

#include "common/io/file_bytes.h"

namespace evoslam {

std::vector<proto::ResultFile> ReadResultFiles(const std::filesystem::path& dir,
                                               std::span<const std::string> names) {
  std::vector<proto::ResultFile> files;
  files.reserve(names.size());
  for (const std::string& name : names) {
    proto::ResultFile& file = files.emplace_back();
    file.set_name(name);
    file.set_content(ReadFileBytes(dir / name));
  }
  return files;
}

}  // namespace evoslam
