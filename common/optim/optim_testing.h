#ifndef EVOSLAM_COMMON_OPTIM_OPTIM_TESTING_H_
#define EVOSLAM_COMMON_OPTIM_OPTIM_TESTING_H_

// Helpers shared by the optimiser tests (header-only; test binaries include it).

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "common/optim/algorithm.h"
#include "common/optim/evolve.h"
#include "common/optim/test_problems.h"

namespace evoslam::testing {

// Sphere centred off the box centre, so that an optimiser that only samples the middle fails.
inline FunctionProblem ShiftedSphere(int dim) {
  return FunctionProblem(
      Eigen::VectorXd::Constant(dim, -5.0), Eigen::VectorXd::Constant(dim, 5.0),
      [](const Eigen::Ref<const Eigen::VectorXd>& x) { return (x.array() - 1.7).square().sum(); });
}

inline FunctionProblem Rosenbrock2() {
  return FunctionProblem(Eigen::Vector2d(-2, -1), Eigen::Vector2d(2, 3),
                         [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                           return 100 * std::pow(x(1) - x(0) * x(0), 2) + std::pow(1 - x(0), 2);
                         });
}

// Runs `algorithm` for `generations` generations from `seed`.
inline OptimResult RunFor(const Problem& problem, Algorithm& algorithm, std::size_t generations,
                          std::uint64_t seed) {
  StopCriteria stop;
  stop.max_generations = generations;
  Rng rng(seed);
  return Minimize(problem, algorithm, stop, rng);
}

// Runs `run` with one and with two OpenMP threads; the results must be the same bits.
template <typename Run>
void ExpectSameBitsWithOneAndTwoThreads(Run run) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const OptimResult one = run();
  omp_set_num_threads(2);
  const OptimResult two = run();
  omp_set_num_threads(saved);
  EXPECT_EQ(one.best_fitness, two.best_fitness);
  EXPECT_EQ(one.best, two.best);
  EXPECT_EQ(one.evaluations, two.evaluations);
}

// Runs `first` for `total` generations straight through, and `second` (built with the same
// parameters) from a state saved by `first`'s twin after `split` generations; both must end on
// the same population, bit for bit.
template <typename Make>
void ExpectResumeMatchesUninterrupted(const Problem& problem, Make make, std::size_t split,
                                      std::size_t total, std::uint64_t seed) {
  auto straight = make();
  Rng rng_straight(seed);
  straight->Initialize(problem, rng_straight);
  for (std::size_t g = 0; g < total; ++g) straight->Step(problem, rng_straight);

  auto before = make();
  Rng rng_before(seed);
  before->Initialize(problem, rng_before);
  for (std::size_t g = 0; g < split; ++g) before->Step(problem, rng_before);
  const AlgorithmState saved = before->Save();
  const RngState rng_saved = rng_before.state();

  auto after = make();
  after->Restore(saved);
  Rng rng_after = Rng::FromState(rng_saved);
  for (std::size_t g = split; g < total; ++g) after->Step(problem, rng_after);

  EXPECT_EQ(after->generation(), straight->generation());
  EXPECT_EQ(after->evaluations(), straight->evaluations());
  EXPECT_EQ(after->population().x, straight->population().x);
  EXPECT_EQ(after->population().f, straight->population().f);
  EXPECT_EQ(after->champion_x(), straight->champion_x());
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_OPTIM_OPTIM_TESTING_H_
