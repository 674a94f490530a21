#include "bench/engines.h"

#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/pso.hpp>
#include <pagmo/algorithms/sga.hpp>
#include <pagmo/archipelago.hpp>
#include <pagmo/islands/thread_island.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/r_policies/fair_replace.hpp>
#include <pagmo/s_policies/select_best.hpp>
#include <pagmo/topologies/ring.hpp>

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "bench/pagmo_problem.h"
#include "common/optim/evolve.h"
#include "common/optim/simple_ga.h"
#include "common/util/error.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// pagmo numbers the ten classic strategies in its own order (pagmo/algorithms/de.hpp).
unsigned PagmoDeVariant(DeStrategy strategy) {
  switch (strategy) {
    case DeStrategy::kBest1Exp:
      return 1;
    case DeStrategy::kRand1Exp:
      return 2;
    case DeStrategy::kRandToBest1Exp:
      return 3;
    case DeStrategy::kBest2Exp:
      return 4;
    case DeStrategy::kRand2Exp:
      return 5;
    case DeStrategy::kBest1Bin:
      return 6;
    case DeStrategy::kRand1Bin:
      return 7;
    case DeStrategy::kRandToBest1Bin:
      return 8;
    case DeStrategy::kBest2Bin:
      return 9;
    case DeStrategy::kRand2Bin:
      return 10;
  }
  throw Error("pagmo has no DE variant for strategy " + std::string(DeStrategyName(strategy)));
}

// pagmo's PSO variant 1 is the inertia-weight update ours uses, v = w v + c1 r1 (p - x) +
// c2 r2 (g - x) with fresh r1, r2 per coordinate; its variant 5 (the default) is the constriction
// form w (v + ...), the same swarm only when c1 and c2 are rescaled by 1 / w.
constexpr unsigned kPagmoPsoInertiaWeight = 1;
constexpr unsigned kPagmoPsoGlobalBest = 1;

}  // namespace

Engine Evoslam(std::function<std::unique_ptr<Algorithm>(std::size_t population)> make) {
  return
      [make = std::move(make)](const Problem& problem, const Budget& budget, std::uint64_t seed) {
        const std::unique_ptr<Algorithm> algorithm = make(budget.population);
        StopCriteria stop;
        stop.max_evaluations = budget.population * (budget.generations + 1);
        Rng rng(seed);
        const OptimResult result = Minimize(problem, *algorithm, stop, rng);
        return EngineRun{result.best_fitness, result.evaluations};
      };
}

Engine Pagmo(std::function<pagmo::algorithm(unsigned generations, unsigned seed)> make) {
  return
      [make = std::move(make)](const Problem& problem, const Budget& budget, std::uint64_t seed) {
        const pagmo::algorithm algorithm =
            make(static_cast<unsigned>(budget.generations), static_cast<unsigned>(MixBits(seed)));
        pagmo::population population(pagmo::problem(PagmoProblem(problem)), budget.population,
                                     static_cast<unsigned>(seed));
        population = algorithm.evolve(population);
        return EngineRun{population.champion_f()[0],
                         static_cast<std::size_t>(population.get_problem().get_fevals())};
      };
}

Engine EvoslamDe(DeParams params) {
  return Evoslam([params](std::size_t population) mutable {
    params.population = population;
    return std::make_unique<DifferentialEvolution>(params);
  });
}

Engine PagmoDe(const DeParams& params) {
  const unsigned variant = PagmoDeVariant(params.strategy);
  return Pagmo([params, variant](unsigned generations, unsigned seed) {
    // ftol = xtol = 0: pagmo would otherwise stop once the population is flat, short of the
    // budget ours spends.
    return pagmo::algorithm(pagmo::de(generations, params.f, params.cr, variant, 0.0, 0.0, seed));
  });
}

Engine EvoslamPso(PsoParams params) {
  return Evoslam([params](std::size_t population) mutable {
    params.particles = population;
    return std::make_unique<ParticleSwarm>(params);
  });
}

Engine PagmoPso(const PsoParams& params) {
  if (params.neighbourhood != PsoNeighbourhood::kGlobal)
    throw Error("pagmo's ring PSO differs from ours; only the global best is compared");
  return Pagmo([params](unsigned generations, unsigned seed) {
    return pagmo::algorithm(pagmo::pso(generations, params.inertia, params.c1, params.c2,
                                       params.vmax_fraction, kPagmoPsoInertiaWeight,
                                       kPagmoPsoGlobalBest, /*neighb_param, unused by gbest=*/4u,
                                       /*memory=*/false, seed));
  });
}

Engine EvoslamSga(GaParams params) {
  return Evoslam([params](std::size_t) { return std::make_unique<SimpleGa>(params); });
}

Engine PagmoSga() {
  return Pagmo([](unsigned generations, unsigned seed) {
    return pagmo::algorithm(pagmo::sga(generations, 0.9, 1.0, 0.02, 1.0, 2u, "exponential",
                                       "polynomial", "tournament", seed));
  });
}

Engine EvoslamIslands(const DeParams& params, const IslandBudget& islands) {
  return [params, islands](const Problem& problem, const Budget& budget, std::uint64_t seed) {
    IslandModelParams model;
    model.islands = islands.islands;
    model.algorithm.kind = AlgorithmKind::kDe;
    model.algorithm.de = params;
    model.algorithm.de.population = budget.population / islands.islands;
    model.migration.interval = islands.interval;
    model.migration.migrants = islands.migrants;
    model.threads = islands.threads;
    model.asynchronous = islands.asynchronous;
    StopCriteria stop;
    stop.max_generations = budget.generations;
    Archipelago archipelago(model, stop, seed);
    archipelago.Run(problem);
    const OptimResult best = archipelago.Best();
    return EngineRun{best.best_fitness, best.evaluations};
  };
}

Engine PagmoIslands(const DeParams& params, const IslandBudget& islands) {
  const unsigned variant = PagmoDeVariant(params.strategy);
  return
      [params, islands, variant](const Problem& problem, const Budget& budget, std::uint64_t seed) {
        const auto per_island = budget.population / islands.islands;
        const auto epochs = static_cast<unsigned>(budget.generations / islands.interval);
        pagmo::archipelago archipelago{pagmo::ring{}};
        for (std::size_t i = 0; i < islands.islands; ++i) {
          const auto island_seed = static_cast<unsigned>(MixBits(seed + 1000 * (i + 1)));
          pagmo::algorithm algorithm(pagmo::de(static_cast<unsigned>(islands.interval), params.f,
                                               params.cr, variant, 0.0, 0.0, island_seed));
          archipelago.push_back(pagmo::thread_island{}, std::move(algorithm),
                                pagmo::problem(PagmoProblem(problem)), per_island,
                                pagmo::r_policy(pagmo::fair_replace(islands.migrants)),
                                pagmo::s_policy(pagmo::select_best(islands.migrants)), island_seed);
        }
        archipelago.evolve(epochs);
        archipelago.wait_check();
        double best = std::numeric_limits<double>::infinity();
        std::size_t evaluations = 0;
        for (const auto& island : archipelago) {
          const pagmo::population population = island.get_population();
          best = std::min(best, population.champion_f()[0]);
          evaluations += static_cast<std::size_t>(population.get_problem().get_fevals());
        }
        return EngineRun{best, evaluations};
      };
}

}  // namespace evoslam
