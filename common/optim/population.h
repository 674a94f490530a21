#ifndef EVOSLAM_COMMON_OPTIM_POPULATION_H_
#define EVOSLAM_COMMON_OPTIM_POPULATION_H_

#include <cstddef>
#include <vector>

#include "common/optim/problem.h"

namespace evoslam {

// Candidates as columns, with their objective values as the matching columns of f (minimised).
struct Population {
  Eigen::MatrixXd x;  // dimension x size
  Eigen::MatrixXd f;  // objectives x size

  std::size_t size() const { return static_cast<std::size_t>(x.cols()); }

  // The lowest first objective; the first such index on ties, so the choice is deterministic.
  std::size_t BestIndex() const;
};

// Column indices of f, best first: ascending first objective, NaN last, ties in index order.
std::vector<std::size_t> RankByFitness(const Eigen::MatrixXd& f);

// Evaluates the columns of x as one batch into f (resized to objectives x cols).
void EvaluateBatch(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& x,
                   Eigen::MatrixXd& f);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_POPULATION_H_
