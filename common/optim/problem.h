#ifndef EVOSLAM_COMMON_OPTIM_PROBLEM_H_
#define EVOSLAM_COMMON_OPTIM_PROBLEM_H_

#include <Eigen/Core>
#include <cstddef>
#include <span>

namespace evoslam {

// A box-bounded minimisation problem evaluated a batch at a time: one generation is one batch, the
// unit that is spread across threads (and, later, workers). Implementations must be thread-safe
// and deterministic: a candidate's fitness may not depend on the batch it arrives in.
class Problem {
 public:
  virtual ~Problem() = default;

  std::size_t dimension() const { return static_cast<std::size_t>(lower().size()); }
  virtual const Eigen::VectorXd& lower() const = 0;
  virtual const Eigen::VectorXd& upper() const = 0;

  // candidates: one column per candidate (dimension() rows); fitness.size() == cols().
  virtual void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                        std::span<double> fitness) const = 0;
};

struct OptimResult {
  Eigen::VectorXd best;
  double best_fitness = 0.0;
  std::size_t evaluations = 0;
  std::size_t generations = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_PROBLEM_H_
