#ifndef EVOSLAM_COMMON_UTIL_COUNTED_H_
#define EVOSLAM_COMMON_UTIL_COUNTED_H_

#include <cstdint>
#include <string>
#include <string_view>

namespace evoslam {

// "1 thread", "2 threads": a count with its noun, plural unless the count is one. For nouns whose
// plural takes an -s.
inline std::string Counted(std::uint64_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_COUNTED_H_
