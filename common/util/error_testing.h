#ifndef EVOSLAM_COMMON_UTIL_ERROR_TESTING_H_
#define EVOSLAM_COMMON_UTIL_ERROR_TESTING_H_

// For tests: what a refusal says.

#include <functional>
#include <string>

#include "common/util/error.h"

namespace evoslam::testing {

// The message of the Error `f` throws; empty when it throws none.
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_UTIL_ERROR_TESTING_H_
