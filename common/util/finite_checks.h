#ifndef EVOSLAM_COMMON_UTIL_FINITE_CHECKS_H_
#define EVOSLAM_COMMON_UTIL_FINITE_CHECKS_H_

#include <cmath>

namespace evoslam {

// The range checks that parameter validation repeats. Both are false for NaN and infinities, so a
// caller need not remember that `x < 0.0` lets NaN through.
inline bool IsFiniteNonNegative(double x) { return std::isfinite(x) && x >= 0.0; }
inline bool IsFinitePositive(double x) { return std::isfinite(x) && x > 0.0; }

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_FINITE_CHECKS_H_
