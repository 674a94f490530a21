#ifndef EVOSLAM_COMMON_UTIL_ERROR_H_
#define EVOSLAM_COMMON_UTIL_ERROR_H_

#include <cstddef>
#include <stdexcept>
#include <string>

namespace evoslam {

// Every failure a user can cause (bad file, bad flag, bad value) is reported as an Error, whose
// message says what went wrong and where; the command line prints it and exits non-zero.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An error at a known place in an input: "FILE:LINE: MESSAGE" (LINE is omitted when 0).
class InputError : public Error {
 public:
  InputError(const std::string& source, std::size_t line, const std::string& message);

  const std::string& source() const { return source_; }
  std::size_t line() const { return line_; }
  const std::string& message() const { return message_; }  // what() without the place

 private:
  std::string source_;
  std::size_t line_;
  std::string message_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_ERROR_H_
