#include "common/util/error.h"

namespace evoslam {
namespace {

std::string Located(const std::string& source, std::size_t line, const std::string& message) {
  std::string where = source;
  if (line > 0) where += ":" + std::to_string(line);
  return where + ": " + message;
}

}  // namespace

InputError::InputError(const std::string& source, std::size_t line, const std::string& message)
    : Error(Located(source, line, message)), source_(source), line_(line), message_(message) {}

}  // namespace evoslam
