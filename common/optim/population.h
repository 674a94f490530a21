#ifndef EVOSLAM_COMMON_OPTIM_POPULATION_H_
#define EVOSLAM_COMMON_OPTIM_POPULATION_H_

#include <cstddef>
#include <vector>

#include "common/optim/problem.h"
#include "common/util/random.h"

namespace evoslam {

// Candidates as columns, with their fitness (minimised).
struct Population {
  Eigen::MatrixXd x;
  std::vector<double> fitness;

  // The lowest fitness; the first such index on ties, so the choice is deterministic.
  std::size_t BestIndex() const;
};

// `size` candidates drawn uniformly in the problem's box, evaluated as one batch.
Population RandomPopulation(const Problem& problem, std::size_t size, Rng& rng);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_POPULATION_H_
