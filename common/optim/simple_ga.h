#ifndef EVOSLAM_COMMON_OPTIM_SIMPLE_GA_H_
#define EVOSLAM_COMMON_OPTIM_SIMPLE_GA_H_

#include <string_view>

#include "common/optim/binary_ga.h"

namespace evoslam {

// 003's simple genetic algorithm: binary chromosomes on the search grid, elitist selection (pairs
// drawn from the best part of the population), two-point or uniform crossover, and elitist
// mutation (mutants drawn in a small box around the best individual); see
// docs/genetic_algorithms.md.
class SimpleGa : public BinaryGa {
 public:
  explicit SimpleGa(const GaParams& params) : BinaryGa(params) {}
  std::string_view name() const override { return "sga"; }

 protected:
  void Breed(const std::vector<std::size_t>& ranking, Rng& rng, Chromosomes& offspring) override;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_SIMPLE_GA_H_
