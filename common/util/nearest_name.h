#ifndef EVOSLAM_COMMON_UTIL_NEAREST_NAME_H_
#define EVOSLAM_COMMON_UTIL_NEAREST_NAME_H_

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace evoslam {

// The fewest single-character insertions, deletions, substitutions and swaps of neighbours that
// turn `a` into `b` (optimal string alignment distance).
std::size_t EditDistance(std::string_view a, std::string_view b);

// The name in `names` closest to `typed`, when it is close enough to be what was meant (within a
// third of the longer name's length, and at least one edit), or else the only name that starts
// with it; for "did you mean" hints.
std::optional<std::string> NearestName(std::string_view typed, std::span<const std::string> names);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_NEAREST_NAME_H_
