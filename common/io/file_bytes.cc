#include "common/io/file_bytes.h"

#include <fstream>
#include <ios>
#include <iterator>
#include <system_error>

#include "common/io/text_file_writer.h"
#include "common/util/error.h"

namespace evoslam {

std::string ReadFileBytes(const std::filesystem::path& path) {
  // A directory opens as a stream on Linux and fails only when read, with a library exception.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path.string(), 0, "is a directory, not a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open");
  try {
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    if (in.bad()) throw InputError(path.string(), 0, "cannot read");
    return bytes;
  } catch (const std::ios_base::failure& e) {
    throw InputError(path.string(), 0, std::string("cannot read: ") + e.what());
  }
}

void WriteFileBytes(const std::filesystem::path& path, std::string_view bytes) {
  TextFileWriter file(path);
  file.Write(bytes);
  file.Close();
}

}  // namespace evoslam
