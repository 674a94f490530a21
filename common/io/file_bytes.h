#ifndef EVOSLAM_COMMON_IO_FILE_BYTES_H_
#define EVOSLAM_COMMON_IO_FILE_BYTES_H_

#include <filesystem>
#include <string>
#include <string_view>

namespace evoslam {

// A whole file's bytes. Throws InputError naming the file when it cannot be opened or read.
std::string ReadFileBytes(const std::filesystem::path& path);

// Replaces the file's contents with `bytes`. Throws Error naming the file when it cannot be
// created, written or closed; a full disk often shows only at the close.
void WriteFileBytes(const std::filesystem::path& path, std::string_view bytes);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_FILE_BYTES_H_
