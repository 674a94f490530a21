#include "common/optim/particle_swarm.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/optim/population.h"
#include "common/util/error.h"

namespace evoslam {

OptimResult RunParticleSwarm(const Problem& problem, const PsoParams& params, Rng& rng) {
  if (params.particles < 2) throw Error("particle swarm: needs at least 2 particles");
  if (!(params.vmax_fraction > 0.0)) throw Error("particle swarm: vmax fraction must be > 0");

  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const Eigen::VectorXd vmax = params.vmax_fraction * (hi - lo);
  const auto dim = lo.size();
  const auto n = static_cast<Eigen::Index>(params.particles);

  Population swarm = RandomPopulation(problem, params.particles, rng);
  Eigen::MatrixXd velocity(dim, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < dim; ++j) velocity(j, i) = rng.Uniform(-vmax(j), vmax(j));
  }
  Population personal = swarm;
  std::size_t global = personal.BestIndex();

  OptimResult result;
  result.evaluations = params.particles;
  for (std::size_t gen = 0; gen < params.generations; ++gen) {
    for (Eigen::Index i = 0; i < n; ++i) {
      for (Eigen::Index j = 0; j < dim; ++j) {
        const double r1 = rng.Uniform();
        const double r2 = rng.Uniform();
        double v =
            params.inertia * velocity(j, i) + params.c1 * r1 * (personal.x(j, i) - swarm.x(j, i)) +
            params.c2 * r2 * (personal.x(j, static_cast<Eigen::Index>(global)) - swarm.x(j, i));
        v = std::clamp(v, -vmax(j), vmax(j));
        double x = swarm.x(j, i) + v;
        if (x < lo(j) || x > hi(j)) {
          x = std::clamp(x, lo(j), hi(j));
          v = 0.0;
        }
        velocity(j, i) = v;
        swarm.x(j, i) = x;
      }
    }
    problem.Evaluate(swarm.x, swarm.fitness);
    result.evaluations += params.particles;
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      if (swarm.fitness[ui] < personal.fitness[ui]) {
        personal.x.col(i) = swarm.x.col(i);
        personal.fitness[ui] = swarm.fitness[ui];
      }
    }
    global = personal.BestIndex();
    result.generations = gen + 1;
  }
  result.best = personal.x.col(static_cast<Eigen::Index>(global));
  result.best_fitness = personal.fitness[global];
  return result;
}

}  // namespace evoslam
