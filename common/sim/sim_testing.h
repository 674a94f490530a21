#ifndef EVOSLAM_COMMON_SIM_SIM_TESTING_H_
#define EVOSLAM_COMMON_SIM_SIM_TESTING_H_

// Helpers shared by the simulator's tests (header-only; test binaries include it).

#include "common/line_map/line_map.h"

namespace evoslam::testing {

// The four walls of a width x height room with a corner at the origin.
inline LineMap Room(double width, double height) {
  const double w = width;
  const double h = height;
  return LineMap({{{0, 0}, {w, 0}}, {{w, 0}, {w, h}}, {{w, h}, {0, h}}, {{0, h}, {0, 0}}});
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_SIM_SIM_TESTING_H_
