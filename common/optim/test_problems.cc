#include "common/optim/test_problems.h"

namespace evoslam {

void FunctionProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                               std::span<double> fitness) const {
  const auto n = candidates.cols();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) fitness[static_cast<std::size_t>(i)] = f_(candidates.col(i));
}

}  // namespace evoslam
