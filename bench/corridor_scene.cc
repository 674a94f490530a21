#include "bench/corridor_scene.h"

#include "common/sim/simulator.h"

namespace evoslam {

const CorridorScene& Corridor() {
  static const CorridorScene scene = [] {
    CorridorScene s{BuiltinWorld("s-corridor"), {}};
    SimulationOptions options;
    options.noise.uniform_bandwidth = 0.2;
    options.seed = 1;
    s.log = Simulate(s.world, options);
    return s;
  }();
  return scene;
}

}  // namespace evoslam
