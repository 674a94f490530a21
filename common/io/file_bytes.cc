#include "common/io/file_bytes.h"

#include <fstream>
#include <iterator>

#include "common/util/error.h"

namespace evoslam {

std::string ReadFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open");
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  if (in.bad()) throw InputError(path.string(), 0, "cannot read");
  return bytes;
}

}  // namespace evoslam
