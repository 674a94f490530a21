#ifndef EVOSLAM_COMMON_OPTIM_PARTICLE_SWARM_H_
#define EVOSLAM_COMMON_OPTIM_PARTICLE_SWARM_H_

#include <cstddef>

#include "common/optim/problem.h"
#include "common/util/random.h"

namespace evoslam {

// Global-best PSO with inertia weight. Defaults are Clerc's constriction-equivalent settings;
// the velocity of each coordinate is clamped to vmax_fraction of the box width.
struct PsoParams {
  std::size_t particles = 25;
  std::size_t generations = 25;
  double inertia = 0.7298;
  double c1 = 1.49618;  // pull towards the particle's own best
  double c2 = 1.49618;  // pull towards the swarm's best
  double vmax_fraction = 0.5;
};

// Each generation moves every particle, evaluates the swarm as one batch, then updates the
// personal and global bests. Particles that leave the box stop at its wall with zero velocity
// along that coordinate.
OptimResult RunParticleSwarm(const Problem& problem, const PsoParams& params, Rng& rng);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_PARTICLE_SWARM_H_
