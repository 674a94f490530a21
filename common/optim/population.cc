#include "common/optim/population.h"

#include <algorithm>

namespace evoslam {

std::size_t Population::BestIndex() const {
  return static_cast<std::size_t>(std::min_element(fitness.begin(), fitness.end()) -
                                  fitness.begin());
}

Population RandomPopulation(const Problem& problem, std::size_t size, Rng& rng) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  Population pop;
  pop.x.resize(lo.size(), static_cast<Eigen::Index>(size));
  for (Eigen::Index i = 0; i < pop.x.cols(); ++i) {
    for (Eigen::Index j = 0; j < pop.x.rows(); ++j) pop.x(j, i) = rng.Uniform(lo(j), hi(j));
  }
  pop.fitness.resize(size);
  problem.Evaluate(pop.x, pop.fitness);
  return pop;
}

}  // namespace evoslam
