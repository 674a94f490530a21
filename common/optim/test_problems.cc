#include "common/optim/test_problems.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "common/util/error.h"

namespace evoslam {

void FunctionProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                               std::span<double> fitness) const {
  const auto n = candidates.cols();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) fitness[static_cast<std::size_t>(i)] = f_(candidates.col(i));
}

TestFunctionProblem::TestFunctionProblem(TestFunction function, int dimension)
    : function_(function) {
  if (dimension < 1 || (function == TestFunction::kRosenbrock && dimension < 2))
    throw Error("test function: dimension " + std::to_string(dimension) + " is too small");
  const double lo = function == TestFunction::kRosenbrock ? -5.0 : -5.12;
  const double hi = function == TestFunction::kRosenbrock ? 10.0 : 5.12;
  lower_ = Eigen::VectorXd::Constant(dimension, lo);
  upper_ = Eigen::VectorXd::Constant(dimension, hi);
}

double TestFunctionProblem::Value(TestFunction function,
                                  const Eigen::Ref<const Eigen::VectorXd>& x) {
  switch (function) {
    case TestFunction::kSphere:
      return x.squaredNorm();
    case TestFunction::kRosenbrock: {
      const Eigen::Index n = x.size();
      const auto head = x.head(n - 1).array();
      const auto tail = x.tail(n - 1).array();
      return (100.0 * (tail - head.square()).square() + (1.0 - head).square()).sum();
    }
    case TestFunction::kRastrigin:
      return 10.0 * static_cast<double>(x.size()) +
             (x.array().square() - 10.0 * (2.0 * std::numbers::pi * x.array()).cos()).sum();
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void TestFunctionProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                                   std::span<double> fitness) const {
  const auto n = candidates.cols();
  // Threads only pay off once a batch holds enough work to hide their start-up.
#pragma omp parallel for schedule(static) if (n * candidates.rows() >= 4096)
  for (Eigen::Index i = 0; i < n; ++i)
    fitness[static_cast<std::size_t>(i)] = Value(function_, candidates.col(i));
}

ZdtProblem::ZdtProblem(int which, int dimension) : which_(which) {
  if (which != 1 && which != 2) throw Error("ZDT problem must be 1 or 2");
  if (dimension < 2) throw Error("ZDT problems need at least 2 coordinates");
  lower_ = Eigen::VectorXd::Zero(dimension);
  upper_ = Eigen::VectorXd::Ones(dimension);
}

double ZdtProblem::FrontF2(double f1) const {
  return which_ == 1 ? 1.0 - std::sqrt(f1) : 1.0 - f1 * f1;
}

void ZdtProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                          std::span<double> fitness) const {
  const auto n = candidates.cols();
  const auto dim = candidates.rows();
#pragma omp parallel for schedule(static) if (n * dim >= 4096)
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto x = candidates.col(i);
    const double f1 = x(0);
    const double g = 1.0 + 9.0 * x.tail(dim - 1).sum() / static_cast<double>(dim - 1);
    const double ratio = f1 / g;
    const double h = which_ == 1 ? 1.0 - std::sqrt(ratio) : 1.0 - ratio * ratio;
    fitness[2 * static_cast<std::size_t>(i)] = f1;
    fitness[2 * static_cast<std::size_t>(i) + 1] = g * h;
  }
}

double InvertedGenerationalDistance(const ZdtProblem& problem, const Eigen::MatrixXd& front,
                                    int samples) {
  double total = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double f1 = static_cast<double>(s) / (samples - 1);
    const Eigen::Vector2d point(f1, problem.FrontF2(f1));
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < front.cols(); ++i)
      nearest = std::min(nearest, (front.col(i).head<2>() - point).norm());
    total += nearest;
  }
  return total / samples;
}

}  // namespace evoslam
