#ifndef EVOSLAM_COMMON_OPTIM_OPTIM_TESTING_H_
#define EVOSLAM_COMMON_OPTIM_OPTIM_TESTING_H_

// Helpers shared by the optimiser tests (header-only; test binaries include it).

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "common/optim/algorithm.h"
#include "common/optim/evolve.h"
#include "common/optim/test_problems.h"
#include "common/util/error.h"

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

// Runs `algorithm` from `seed`: Initialize, then `generations` steps (any number of objectives).
inline void RunGenerations(const Problem& problem, Algorithm& algorithm, std::size_t generations,
                           std::uint64_t seed) {
  Rng rng(seed);
  algorithm.Initialize(problem, rng);
  for (std::size_t g = 0; g < generations; ++g) algorithm.Step(problem, rng);
}

// Wraps a problem and keeps a copy of every batch it evaluates, so that a test can inspect the
// candidates an algorithm makes.
class RecordingProblem : public Problem {
 public:
  explicit RecordingProblem(const Problem& inner) : inner_(inner) {}
  const Eigen::VectorXd& lower() const override { return inner_.lower(); }
  const Eigen::VectorXd& upper() const override { return inner_.upper(); }
  Encoding encoding() const override { return inner_.encoding(); }
  std::size_t objectives() const override { return inner_.objectives(); }
  const Immunity* immunity() const override { return inner_.immunity(); }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override {
    inner_.Evaluate(candidates, fitness);
    const std::lock_guard<std::mutex> lock(mutex_);
    batches_.emplace_back(candidates);
  }
  const std::vector<Eigen::MatrixXd>& batches() const { return batches_; }

 private:
  const Problem& inner_;
  mutable std::mutex mutex_;
  mutable std::vector<Eigen::MatrixXd> batches_;
};

// Runs `make()`'s algorithm for `generations` generations with one and with two OpenMP threads;
// the final populations must be the same bits.
template <typename Make>
void ExpectSamePopulationWithOneAndTwoThreads(const Problem& problem, Make make,
                                              std::size_t generations, std::uint64_t seed) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  auto one = make();
  RunGenerations(problem, *one, generations, seed);
  omp_set_num_threads(2);
  auto two = make();
  RunGenerations(problem, *two, generations, seed);
  omp_set_num_threads(saved);
  EXPECT_EQ(one->population().x, two->population().x);
  EXPECT_EQ(one->population().f, two->population().f);
  EXPECT_EQ(one->evaluations(), two->evaluations());
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
// the same population, bit for bit. `also(after, straight)` may compare what else the algorithm
// keeps.
template <typename Make, typename Also = void (*)(const Algorithm&, const Algorithm&)>
void ExpectResumeMatchesUninterrupted(
    const Problem& problem, Make make, std::size_t split, std::size_t total, std::uint64_t seed,
    Also also = [](const Algorithm&, const Algorithm&) {}) {
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
  also(*after, *straight);
}

// Builds Algo from default Params changed by `change`; the constructor must refuse them with an
// Error whose message contains `words`.
template <typename Algo, typename Params, typename Change>
void ExpectRejected(Change change, const std::string& words) {
  Params params;
  change(params);
  try {
    Algo algorithm(params);
    ADD_FAILURE() << "accepted parameters that should fail with: " << words;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_OPTIM_OPTIM_TESTING_H_
