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

std::size_t Population::WorstIndex() const {
  std::size_t worst = 0;
  for (Eigen::Index i = 1; i < f.cols(); ++i) {
    if (f(0, i) >= f(0, static_cast<Eigen::Index>(worst))) worst = static_cast<std::size_t>(i);
  }
  return worst;
}

void EvaluateBatch(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& x,
                   Eigen::MatrixXd& f) {
  f.resize(static_cast<Eigen::Index>(problem.objectives()), x.cols());
  problem.Evaluate(x, std::span<double>(f.data(), static_cast<std::size_t>(f.size())));
}

Population RandomPopulation(const Problem& problem, std::size_t size, Rng& rng) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  Population pop;
  pop.x.resize(lo.size(), static_cast<Eigen::Index>(size));
  for (Eigen::Index i = 0; i < pop.x.cols(); ++i) {
    for (Eigen::Index j = 0; j < pop.x.rows(); ++j) pop.x(j, i) = rng.Uniform(lo(j), hi(j));
    Conform(problem, pop.x.col(i));
  }
  EvaluateBatch(problem, pop.x, pop.f);
  return pop;
}

}  // namespace evoslam
