#include "common/optim/evolve.h"

#include <chrono>
#include <string>

#include "common/util/error.h"

namespace evoslam {

std::optional<StopReason> Advance(const Problem& problem, Algorithm& algorithm,
                                  StopTracker& tracker, Rng& rng, std::size_t max_generations) {
  const auto start = std::chrono::steady_clock::now();
  const double before = tracker.progress().elapsed_seconds;
  const auto elapsed = [&] {
    return before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  for (std::size_t step = 0; step < max_generations; ++step) {
    if (const auto reason = tracker.Check(algorithm)) return reason;
    algorithm.Step(problem, rng);
    tracker.Update(algorithm, elapsed());
  }
  return tracker.Check(algorithm);
}

OptimResult Minimize(const Problem& problem, Algorithm& algorithm, const StopCriteria& criteria,
                     Rng& rng) {
  ValidateStopCriteria(criteria);
  if (problem.objectives() != 1) {
    throw Error(std::string(algorithm.name()) +
                ": Minimize needs a single-objective problem, got " +
                std::to_string(problem.objectives()) + " objectives");
  }
  const auto start = std::chrono::steady_clock::now();
  algorithm.Initialize(problem, rng);
  StopTracker tracker(criteria);
  tracker.Update(algorithm,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  Advance(problem, algorithm, tracker, rng);
  OptimResult result;
  result.best = algorithm.champion_x();
  result.best_fitness = algorithm.champion_f().size() > 0
                            ? algorithm.champion_f()(0)
                            : std::numeric_limits<double>::quiet_NaN();
  result.evaluations = algorithm.evaluations();
  result.generations = algorithm.generation();
  return result;
}

}  // namespace evoslam
