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

// The classic benchmark functions, with their usual boxes; the minimum is 0 for all three.
enum class TestFunction {
  kSphere,      // sum x^2 on [-5.12, 5.12]^n, minimum at 0
  kRosenbrock,  // on [-5, 10]^n, minimum at (1, ..., 1)
  kRastrigin,   // 10 n + sum (x^2 - 10 cos 2 pi x) on [-5.12, 5.12]^n, minimum at 0
};

class TestFunctionProblem : public Problem {
 public:
  TestFunctionProblem(TestFunction function, int dimension);
  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

  static double Value(TestFunction function, const Eigen::Ref<const Eigen::VectorXd>& x);

 private:
  TestFunction function_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
};

// Zitzler, Deb and Thiele's two-objective problems on [0, 1]^n. Pareto-optimal where
// x_2..x_n = 0: ZDT1's front is f2 = 1 - sqrt(f1) (convex), ZDT2's f2 = 1 - f1^2 (concave).
class ZdtProblem : public Problem {
 public:
  ZdtProblem(int which, int dimension);  // which: 1 or 2
  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  std::size_t objectives() const override { return 2; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

  // The true front's f2 at f1.
  double FrontF2(double f1) const;
  int which() const { return which_; }

 private:
  int which_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
};

// Inverted generational distance: mean distance from `samples` points evenly spread along the
// problem's true front to the nearest point of `front` (objectives x n). 0 is a perfect front.
double InvertedGenerationalDistance(const ZdtProblem& problem, const Eigen::MatrixXd& front,
                                    int samples = 200);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_TEST_PROBLEMS_H_
