#ifndef EVOSLAM_BENCH_ENGINES_H_
#define EVOSLAM_BENCH_ENGINES_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <pagmo/algorithm.hpp>

#include "common/engine/archipelago.h"
#include "common/optim/algorithm.h"
#include "common/optim/differential_evolution.h"
#include "common/optim/ga_params.h"
#include "common/optim/particle_swarm.h"

namespace evoslam {

// What either engine gets: `population` individuals, evaluated once at the start and once per
// generation, so that a run costs population * (generations + 1) evaluations on both sides.
struct Budget {
  std::size_t population = 0;
  std::size_t generations = 0;
};

struct EngineRun {
  double best_fitness = 0.0;  // the best fitness ever evaluated
  std::size_t evaluations = 0;
};

// One seeded single-objective run on a problem within a budget.
using Engine = std::function<EngineRun(const Problem&, const Budget&, std::uint64_t seed)>;

// Our engine: Minimize with the algorithm that `make` builds for a population size, stopped by
// the budget's evaluations (so algorithms that evaluate fewer candidates a generation than their
// population, like the SGA, run more generations).
Engine Evoslam(std::function<std::unique_ptr<Algorithm>(std::size_t population)> make);
// pagmo's: the algorithm that `make` builds for a number of generations and a seed evolves a
// pagmo population of the budget's size. The population and the algorithm draw from different
// seeds derived from the run's.
Engine Pagmo(std::function<pagmo::algorithm(unsigned generations, unsigned seed)> make);

// The same algorithm and settings on each side; the population size comes from the budget.
Engine EvoslamDe(DeParams params);
Engine PagmoDe(const DeParams& params);
Engine EvoslamPso(PsoParams params);
// Global best only: pagmo's ring (lbest) leaves the particle itself out of its neighbourhood,
// ours does not, so the two rings are different algorithms. Throws Error for the ring.
Engine PagmoPso(const PsoParams& params);

// 003's SGA with `params` (its own population; 12 new candidates a generation) against pagmo's
// real-coded SGA (tournament selection, exponential crossover, polynomial mutation, its defaults)
// with the budget's population.
Engine EvoslamSga(GaParams params);
Engine PagmoSga();

// Island models of DE: `islands` islands sharing the budget's population evenly, migrating
// `migrants` best individuals along a ring every `interval` generations, on `threads` threads.
// pagmo's counterpart is an archipelago of thread islands with a ring topology and its default
// policies (best migrants, fair replacement).
struct IslandBudget {
  std::size_t islands = 4;
  std::size_t interval = 10;
  std::size_t migrants = 1;
  std::size_t threads = 2;
  bool asynchronous = false;  // ours only
  // pagmo only: evolve one epoch at a time and wait for all islands, so that no island runs ahead
  // of the others (pagmo's islands otherwise drift apart).
  bool lockstep = false;
};
Engine EvoslamIslands(const DeParams& params, const IslandBudget& islands);
Engine PagmoIslands(const DeParams& params, const IslandBudget& islands);

}  // namespace evoslam

#endif  // EVOSLAM_BENCH_ENGINES_H_
