#ifndef EVOSLAM_BENCH_CORRIDOR_SCENE_H_
#define EVOSLAM_BENCH_CORRIDOR_SCENE_H_

#include "common/sensor/dataset.h"
#include "common/sim/world.h"

namespace evoslam {

struct CorridorScene {
  World world;
  Dataset log;
};

// The s-shaped corridor with 20 cm uniform noise, as in the accuracy test: simulated once, on
// first use, and shared by every benchmark that localizes in it.
const CorridorScene& Corridor();

}  // namespace evoslam

#endif  // EVOSLAM_BENCH_CORRIDOR_SCENE_H_
