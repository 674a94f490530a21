#ifndef EVOSLAM_COMMON_TRANSFORM_ANGLE_UNITS_H_
#define EVOSLAM_COMMON_TRANSFORM_ANGLE_UNITS_H_

#include <numbers>

namespace evoslam {

// The code works in radians; flags, reports and summaries speak degrees.
inline constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double Degrees(double radians) { return radians * 180.0 / std::numbers::pi; }
constexpr double Radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_TRANSFORM_ANGLE_UNITS_H_
