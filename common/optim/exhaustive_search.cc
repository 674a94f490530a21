#include "common/optim/exhaustive_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/util/error.h"

namespace evoslam {

OptimResult RunExhaustiveSearch(const Problem& problem, const Eigen::VectorXd& steps) {
  return RunExhaustiveSearch(
      problem, steps,
      [&problem](const Eigen::Ref<const Eigen::MatrixXd>& candidates, std::span<double> fitness) {
        problem.Evaluate(candidates, fitness);
      });
}

OptimResult RunExhaustiveSearch(const Problem& problem, const Eigen::VectorXd& steps,
                                const LatticeEvaluator& evaluate) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const Eigen::Index dim = lo.size();
  if (steps.size() != dim) throw Error("exhaustive search: one step per coordinate is needed");

  std::vector<std::size_t> counts(static_cast<std::size_t>(dim));
  std::size_t total = 1;
  for (Eigen::Index j = 0; j < dim; ++j) {
    if (steps(j) < 0.0) throw Error("exhaustive search: steps must be >= 0");
    const double width = hi(j) - lo(j);
    // The small slack keeps the upper bound when rounding leaves width/step just below an integer.
    const std::size_t n =
        steps(j) > 0.0 ? static_cast<std::size_t>(std::floor(width / steps(j) + 1e-9)) + 1 : 1;
    counts[static_cast<std::size_t>(j)] = n;
    total *= n;
  }
  const auto point = [&](std::size_t index, Eigen::Ref<Eigen::VectorXd> x) {
    for (Eigen::Index j = 0; j < dim; ++j) {
      const std::size_t n = counts[static_cast<std::size_t>(j)];
      const std::size_t k = index % n;
      index /= n;
      x(j) = steps(j) > 0.0 ? lo(j) + static_cast<double>(k) * steps(j) : 0.5 * (lo(j) + hi(j));
    }
  };

  // Batches bound the memory however fine the lattice is.
  constexpr std::size_t kBatch = 4096;
  Eigen::MatrixXd batch(dim, static_cast<Eigen::Index>(kBatch));
  std::vector<double> fitness(kBatch);
  OptimResult result;
  result.best.resize(dim);
  result.best_fitness = std::numeric_limits<double>::infinity();
  for (std::size_t first = 0; first < total; first += kBatch) {
    const std::size_t count = std::min(kBatch, total - first);
    for (std::size_t k = 0; k < count; ++k)
      point(first + k, batch.col(static_cast<Eigen::Index>(k)));
    evaluate(batch.leftCols(static_cast<Eigen::Index>(count)),
             std::span<double>(fitness.data(), count));
    for (std::size_t k = 0; k < count; ++k) {
      if (fitness[k] < result.best_fitness) {
        result.best_fitness = fitness[k];
        result.best = batch.col(static_cast<Eigen::Index>(k));
      }
    }
    ++result.generations;
  }
  result.evaluations = total;
  return result;
}

}  // namespace evoslam
