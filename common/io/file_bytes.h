#ifndef EVOSLAM_COMMON_IO_FILE_BYTES_H_
#define EVOSLAM_COMMON_IO_FILE_BYTES_H_

#include <filesystem>
#include <string>

namespace evoslam {

// A whole file's bytes. Throws InputError naming the file when it cannot be opened or read.
std::string ReadFileBytes(const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_FILE_BYTES_H_
