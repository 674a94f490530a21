#include "bench/pagmo_problem.h"

#include <span>

namespace evoslam {

pagmo::vector_double PagmoProblem::fitness(const pagmo::vector_double& x) const {
  const Eigen::Map<const Eigen::MatrixXd> candidate(x.data(), static_cast<Eigen::Index>(x.size()),
                                                    1);
  pagmo::vector_double f(problem_->objectives());
  problem_->Evaluate(candidate, std::span<double>(f));
  return f;
}

std::pair<pagmo::vector_double, pagmo::vector_double> PagmoProblem::get_bounds() const {
  const Eigen::VectorXd& lo = problem_->lower();
  const Eigen::VectorXd& hi = problem_->upper();
  return {pagmo::vector_double(lo.data(), lo.data() + lo.size()),
          pagmo::vector_double(hi.data(), hi.data() + hi.size())};
}

}  // namespace evoslam
