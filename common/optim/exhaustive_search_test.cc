#include "common/optim/exhaustive_search.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/optim/test_problems.h"

namespace evoslam {
namespace {

TEST(ExhaustiveSearchTest, FindsLatticeMinimumIncludingUpperBound) {
  const FunctionProblem problem(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  return std::abs(x(0) - 1.0) + std::abs(x(1) - 0.3);
                                });
  const OptimResult r = RunExhaustiveSearch(problem, Eigen::Vector2d(0.1, 0.1));
  EXPECT_EQ(r.evaluations, 121u);
  EXPECT_NEAR(r.best(0), 1.0, 1e-12);
  EXPECT_NEAR(r.best(1), 0.3, 1e-12);
}

TEST(ExhaustiveSearchTest, ZeroStepUsesCentreAndLargeLatticesAreBatched) {
  const FunctionProblem problem(Eigen::Vector3d(-1, -1, 2), Eigen::Vector3d(1, 1, 4),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  return std::pow(x(0) - 0.25, 2) + std::pow(x(1) + 0.5, 2) + x(2);
                                });
  const OptimResult r = RunExhaustiveSearch(problem, Eigen::Vector3d(0.01, 0.01, 0.0));
  EXPECT_EQ(r.evaluations, 201u * 201u);
  EXPECT_GT(r.generations, 1u);
  EXPECT_NEAR(r.best(0), 0.25, 1e-9);
  EXPECT_NEAR(r.best(1), -0.5, 1e-9);
  EXPECT_DOUBLE_EQ(r.best(2), 3.0);
}

}  // namespace
}  // namespace evoslam
