#include "common/optim/population.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>

namespace evoslam {

std::size_t Population::BestIndex() const {
  std::size_t best = 0;
  for (Eigen::Index i = 1; i < f.cols(); ++i) {
    if (f(0, i) < f(0, static_cast<Eigen::Index>(best))) best = static_cast<std::size_t>(i);
  }
  return best;
}

std::vector<std::size_t> RankByFitness(const Eigen::MatrixXd& f) {
  std::vector<std::size_t> order(static_cast<std::size_t>(f.cols()));
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto value = [&](std::size_t i) { return f(0, static_cast<Eigen::Index>(i)); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return !std::isnan(value(i)) && (std::isnan(value(j)) || value(i) < value(j));
  });
  return order;
}

void EvaluateBatch(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& x,
                   Eigen::MatrixXd& f) {
  f.resize(static_cast<Eigen::Index>(problem.objectives()), x.cols());
  problem.Evaluate(x, std::span<double>(f.data(), static_cast<std::size_t>(f.size())));
}

}  // namespace evoslam
