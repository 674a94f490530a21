#ifndef EVOSLAM_BENCH_SERIAL_TEST_FUNCTION_H_
#define EVOSLAM_BENCH_SERIAL_TEST_FUNCTION_H_

#include <span>

#include "common/optim/test_problems.h"

namespace evoslam {

// A test function evaluated on the calling thread, candidate after candidate. TestFunctionProblem
// enters an OpenMP region per batch, which costs little per batch of 50 but more than the sphere
// itself per batch of one, the batch pagmo hands over: the engine benchmarks would time libgomp.
class SerialTestFunction : public Problem {
 public:
  SerialTestFunction(TestFunction function, int dimension)
      : function_(function), box_(function, dimension) {}

  const Eigen::VectorXd& lower() const override { return box_.lower(); }
  const Eigen::VectorXd& upper() const override { return box_.upper(); }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override {
    for (Eigen::Index i = 0; i < candidates.cols(); ++i)
      fitness[static_cast<std::size_t>(i)] =
          TestFunctionProblem::Value(function_, candidates.col(i));
  }

 private:
  TestFunction function_;
  TestFunctionProblem box_;  // for its bounds
};

}  // namespace evoslam

#endif  // EVOSLAM_BENCH_SERIAL_TEST_FUNCTION_H_
