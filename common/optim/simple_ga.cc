#include "common/optim/simple_ga.h"

#include "common/optim/ga_operators.h"

namespace evoslam {

void SimpleGa::Breed(const std::vector<std::size_t>& ranking, Rng& rng, Chromosomes& offspring) {
  const GaParams& p = params();
  const Chromosomes& parents = chromosomes();
  const std::size_t pool = MatingPoolSize(p);
  Eigen::Index next = 0;
  for (std::size_t pair = 0; pair < p.pairs; ++pair, next += 2) {
    const auto [a, b] = DrawMates(ranking, pool, rng);
    CrossChromosomes(p.crossover, p.bits, parents.col(static_cast<Eigen::Index>(a)),
                     parents.col(static_cast<Eigen::Index>(b)), rng, offspring.col(next),
                     offspring.col(next + 1));
  }
  const auto best = parents.col(static_cast<Eigen::Index>(ranking.front()));
  for (std::size_t m = 0; m < p.mutants; ++m, ++next)
    MutateNearBest(best, coding().max_code(), p.mutation_box, rng, offspring.col(next));
}

}  // namespace evoslam
