#ifndef EVOSLAM_COMMON_UTIL_INFINITY_H_
#define EVOSLAM_COMMON_UTIL_INFINITY_H_

#include <limits>

namespace evoslam {

// Geometry and ranking code use it for "no bound" and "never reached".
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_INFINITY_H_
