#include "common/optim/population.h"

#include <span>

namespace evoslam {

std::size_t Population::BestIndex() const {
  std::size_t best = 0;
  for (Eigen::Index i = 1; i < f.cols(); ++i) {
    if (f(0, i) < f(0, static_cast<Eigen::Index>(best))) best = static_cast<std::size_t>(i);
  }
  return best;
}

void EvaluateBatch(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& x,
                   Eigen::MatrixXd& f) {
  f.resize(static_cast<Eigen::Index>(problem.objectives()), x.cols());
  problem.Evaluate(x, std::span<double>(f.data(), static_cast<std::size_t>(f.size())));
}

}  // namespace evoslam
