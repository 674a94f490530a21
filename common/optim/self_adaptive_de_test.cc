#include "common/optim/self_adaptive_de.h"

#include <gtest/gtest.h>

#include <memory>

#include "common/optim/optim_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::ExpectResumeMatchesUninterrupted;
using testing::Rosenbrock2;
using testing::RunFor;
using testing::ShiftedSphere;

TEST(SelfAdaptiveDeTest, ConvergesOnShiftedSphere) {
  SelfAdaptiveDe jde(JdeParams{});
  const OptimResult r = RunFor(ShiftedSphere(5), jde, 300, 2);
  EXPECT_LT(r.best_fitness, 1e-10);
}

TEST(SelfAdaptiveDeTest, SolvesRosenbrockIn5Dimensions) {
  JdeParams params;
  params.population = 40;
  SelfAdaptiveDe jde(params);
  const OptimResult r = RunFor(TestFunctionProblem(TestFunction::kRosenbrock, 5), jde, 1500, 3);
  EXPECT_LT(r.best_fitness, 1e-6);
}

TEST(SelfAdaptiveDeTest, BeatsBadlyTunedClassicDeOnRastrigin) {
  // Classic DE with CR 0.9 is poorly suited to the separable Rastrigin; jDE learns a low CR.
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  double jde_total = 0.0, de_total = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    JdeParams jp;
    jp.population = 40;
    SelfAdaptiveDe jde(jp);
    jde_total += RunFor(problem, jde, 400, seed).best_fitness;
    DeParams dp;
    dp.strategy = DeStrategy::kRand1Bin;
    dp.population = 40;
    dp.f = 0.5;
    dp.cr = 0.9;
    DifferentialEvolution de(dp);
    de_total += RunFor(problem, de, 400, seed).best_fitness;
  }
  EXPECT_LT(jde_total, 0.5 * de_total);
  EXPECT_LT(jde_total / 5, 1.0);
}

TEST(SelfAdaptiveDeTest, ControlParametersAdaptWithinTheirRanges) {
  SelfAdaptiveDe jde(JdeParams{});
  Rng rng(4);
  const TestFunctionProblem problem(TestFunction::kRastrigin, 10);
  jde.Initialize(problem, rng);
  for (int g = 0; g < 100; ++g) jde.Step(problem, rng);
  const Eigen::MatrixXd control = jde.Save().memory.at("control");
  EXPECT_GE(control.row(0).minCoeff(), 0.1);
  EXPECT_LT(control.row(0).maxCoeff(), 1.0);
  EXPECT_GE(control.row(1).minCoeff(), 0.0);
  EXPECT_LT(control.row(1).maxCoeff(), 1.0);
  // Something was learnt: not every individual still has the initial values.
  EXPECT_TRUE((control.row(0).array() != 0.5).any());
  EXPECT_TRUE((control.row(1).array() != 0.9).any());
}

TEST(SelfAdaptiveDeTest, ResumedRunMatchesUninterrupted) {
  ExpectResumeMatchesUninterrupted(
      Rosenbrock2(), [] { return std::make_unique<SelfAdaptiveDe>(JdeParams{}); }, 9, 25, 8);
}

TEST(SelfAdaptiveDeTest, RejectsBadParameters) {
  JdeParams p;
  p.tau_f = 1.5;
  EXPECT_THROW(SelfAdaptiveDe{p}, Error);
  JdeParams q;
  q.f_lower = 0.0;
  EXPECT_THROW(SelfAdaptiveDe{q}, Error);
  JdeParams r;
  r.population = 3;
  EXPECT_THROW(SelfAdaptiveDe{r}, Error);
}

}  // namespace
}  // namespace evoslam
