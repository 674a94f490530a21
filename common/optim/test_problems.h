#ifndef EVOSLAM_COMMON_OPTIM_TEST_PROBLEMS_H_
#define EVOSLAM_COMMON_OPTIM_TEST_PROBLEMS_H_

#include <functional>
#include <utility>

#include "common/optim/problem.h"

namespace evoslam {

// A box-bounded problem from a plain function, evaluated in parallel (OpenMP) like the real ones.
class FunctionProblem : public Problem {
 public:
  using Function = std::function<double(const Eigen::Ref<const Eigen::VectorXd>&)>;
  FunctionProblem(Eigen::VectorXd lower, Eigen::VectorXd upper, Function f)
      : lower_(std::move(lower)), upper_(std::move(upper)), f_(std::move(f)) {}

  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

 private:
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
  Function f_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_TEST_PROBLEMS_H_
