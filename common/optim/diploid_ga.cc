#include "common/optim/diploid_ga.h"

#include <utility>

#include "common/optim/ga_operators.h"

namespace evoslam {

void AdaptiveGa::DoInitialize(const Problem& problem, Rng& rng) {
  BinaryGa::DoInitialize(problem, rng);
  dormant_.resize(chromosomes().rows(), chromosomes().cols());
  for (Eigen::Index i = 0; i < dormant_.cols(); ++i) dormant_.col(i) = coding().Random(rng);
}

void AdaptiveGa::Breed(const std::vector<std::size_t>& ranking, Rng& rng, Chromosomes& offspring) {
  const GaParams& p = params();
  const Chromosomes& expressed = chromosomes();
  const std::size_t pool = MatingPoolSize(p);
  offspring_dormant_.resize(offspring.rows(), offspring.cols());
  Eigen::Index next = 0;
  for (std::size_t pair = 0; pair < p.pairs; ++pair) {
    const auto [a, b] = DrawMates(ranking, pool, rng);
    for (const auto& [self, mate] : {std::pair{a, b}, std::pair{b, a}}) {
      CrossChromosomes(p.crossover, p.bits, expressed.col(static_cast<Eigen::Index>(self)),
                       dormant_.col(static_cast<Eigen::Index>(mate)), rng, offspring.col(next),
                       offspring_dormant_.col(next));
      ++next;
    }
  }
  const auto best = expressed.col(static_cast<Eigen::Index>(ranking.front()));
  for (std::size_t m = 0; m < p.mutants; ++m, ++next) {
    MutateNearBest(best, coding().max_code(), p.mutation_box, rng, offspring.col(next));
    offspring_dormant_.col(next) =
        dormant_.col(static_cast<Eigen::Index>(rng.UniformIndex(dormant_.cols())));
  }
}

void AdaptiveGa::Settle(std::size_t index, std::size_t candidate) {
  dormant_.col(static_cast<Eigen::Index>(index)) =
      offspring_dormant_.col(static_cast<Eigen::Index>(candidate));
}

void AdaptiveGa::SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const {
  BinaryGa::SaveMemory(memory);
  memory["dormant"] = ChromosomesToMemory(dormant_);
}

void AdaptiveGa::RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) {
  BinaryGa::RestoreMemory(memory);
  dormant_ = ChromosomesFromMemory(
      MemoryEntry(memory, "dormant", chromosomes().rows(), chromosomes().cols()), params().bits,
      "dormant");
}

}  // namespace evoslam
