#include "common/optim/differential_evolution.h"

#include <algorithm>
#include <array>

#include "common/optim/population.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

struct StrategyInfo {
  DeStrategy strategy;
  std::string_view name;
};

constexpr std::array<StrategyInfo, 10> kStrategies = {{
    {DeStrategy::kRand1Bin, "rand1bin"},
    {DeStrategy::kRand1Exp, "rand1exp"},
    {DeStrategy::kBest1Bin, "best1bin"},
    {DeStrategy::kBest1Exp, "best1exp"},
    {DeStrategy::kRandToBest1Bin, "randtobest1bin"},
    {DeStrategy::kRandToBest1Exp, "randtobest1exp"},
    {DeStrategy::kBest2Bin, "best2bin"},
    {DeStrategy::kBest2Exp, "best2exp"},
    {DeStrategy::kRand2Bin, "rand2bin"},
    {DeStrategy::kRand2Exp, "rand2exp"},
}};

bool IsExponential(DeStrategy s) {
  switch (s) {
    case DeStrategy::kRand1Exp:
    case DeStrategy::kBest1Exp:
    case DeStrategy::kRandToBest1Exp:
    case DeStrategy::kBest2Exp:
    case DeStrategy::kRand2Exp:
      return true;
    default:
      return false;
  }
}

// How many random population members a strategy's mutant uses besides the target and the best.
std::size_t RandomMembers(DeStrategy s) {
  switch (s) {
    case DeStrategy::kRand1Bin:
    case DeStrategy::kRand1Exp:
      return 3;
    case DeStrategy::kBest2Bin:
    case DeStrategy::kBest2Exp:
      return 4;
    case DeStrategy::kRand2Bin:
    case DeStrategy::kRand2Exp:
      return 5;
    default:
      return 2;
  }
}

// Draws `count` (<= 5) distinct indices in [0, n), all different from `exclude`.
std::array<std::size_t, 5> DistinctIndices(std::size_t count, std::size_t n, std::size_t exclude,
                                           Rng& rng) {
  std::array<std::size_t, 5> out{};
  for (std::size_t k = 0; k < count; ++k) {
    std::size_t candidate;
    do {
      candidate = rng.UniformIndex(n);
    } while (candidate == exclude ||
             std::find(out.begin(), out.begin() + k, candidate) != out.begin() + k);
    out[k] = candidate;
  }
  return out;
}

Eigen::VectorXd Mutant(DeStrategy s, const Eigen::MatrixXd& pop, std::size_t i, std::size_t best,
                       double f, Rng& rng) {
  const std::size_t n = static_cast<std::size_t>(pop.cols());
  const auto r = DistinctIndices(RandomMembers(s), n, i, rng);
  const auto x = [&](std::size_t k) { return pop.col(static_cast<Eigen::Index>(k)); };
  switch (s) {
    case DeStrategy::kRand1Bin:
    case DeStrategy::kRand1Exp:
      return x(r[0]) + f * (x(r[1]) - x(r[2]));
    case DeStrategy::kBest1Bin:
    case DeStrategy::kBest1Exp:
      return x(best) + f * (x(r[0]) - x(r[1]));
    case DeStrategy::kRandToBest1Bin:
    case DeStrategy::kRandToBest1Exp:
      return x(i) + f * (x(best) - x(i)) + f * (x(r[0]) - x(r[1]));
    case DeStrategy::kBest2Bin:
    case DeStrategy::kBest2Exp:
      return x(best) + f * (x(r[0]) + x(r[1]) - x(r[2]) - x(r[3]));
    case DeStrategy::kRand2Bin:
    case DeStrategy::kRand2Exp:
      return x(r[4]) + f * (x(r[0]) + x(r[1]) - x(r[2]) - x(r[3]));
  }
  throw Error("differential evolution: unknown strategy");
}

// The vector a strategy starts from, used to pull out-of-box coordinates back inside.
Eigen::VectorXd BaseOf(DeStrategy s, const Eigen::MatrixXd& pop, std::size_t i, std::size_t best) {
  switch (s) {
    case DeStrategy::kBest1Bin:
    case DeStrategy::kBest1Exp:
    case DeStrategy::kBest2Bin:
    case DeStrategy::kBest2Exp:
      return pop.col(static_cast<Eigen::Index>(best));
    default:
      return pop.col(static_cast<Eigen::Index>(i));
  }
}

}  // namespace

DeStrategy ParseDeStrategy(std::string_view name) {
  for (const auto& info : kStrategies) {
    if (info.name == name) return info.strategy;
  }
  std::string valid;
  for (const auto& info : kStrategies)
    valid += (valid.empty() ? "" : ", ") + std::string(info.name);
  throw Error("unknown DE strategy '" + std::string(name) + "' (expected one of: " + valid + ")");
}

std::string_view DeStrategyName(DeStrategy strategy) {
  for (const auto& info : kStrategies) {
    if (info.strategy == strategy) return info.name;
  }
  return "unknown";
}

std::vector<std::string> DeStrategyNames() {
  std::vector<std::string> names;
  for (const auto& info : kStrategies) names.emplace_back(info.name);
  return names;
}

OptimResult RunDifferentialEvolution(const Problem& problem, const DeParams& params, Rng& rng) {
  const std::size_t needed = RandomMembers(params.strategy) + 1;
  if (params.population < needed) {
    throw Error("differential evolution: population " + std::to_string(params.population) +
                " is too small for strategy " + std::string(DeStrategyName(params.strategy)) +
                " (needs at least " + std::to_string(needed) + ")");
  }
  if (!(params.f > 0.0 && params.f <= 2.0))
    throw Error("differential evolution: F must be in (0, 2]");
  if (!(params.cr >= 0.0 && params.cr <= 1.0))
    throw Error("differential evolution: CR must be in [0, 1]");

  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const auto dim = static_cast<Eigen::Index>(problem.dimension());
  const auto np = static_cast<Eigen::Index>(params.population);

  Population pop = RandomPopulation(problem, params.population, rng);
  OptimResult result;
  result.evaluations = params.population;

  Eigen::MatrixXd trials(dim, np);
  std::vector<double> trial_fitness(params.population);
  const bool exponential = IsExponential(params.strategy);

  for (std::size_t gen = 0; gen < params.generations; ++gen) {
    const std::size_t best = pop.BestIndex();
    for (Eigen::Index i = 0; i < np; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      const Eigen::VectorXd mutant = Mutant(params.strategy, pop.x, ui, best, params.f, rng);
      const Eigen::VectorXd base = BaseOf(params.strategy, pop.x, ui, best);
      Eigen::VectorXd trial = pop.x.col(i);
      const Eigen::Index start =
          static_cast<Eigen::Index>(rng.UniformIndex(static_cast<std::size_t>(dim)));
      if (exponential) {
        // A run of consecutive genes, starting at a random one, continued while rand < CR.
        Eigen::Index len = 0;
        do {
          const Eigen::Index j = (start + len) % dim;
          trial(j) = mutant(j);
          ++len;
        } while (len < dim && rng.Uniform() < params.cr);
      } else {
        for (Eigen::Index j = 0; j < dim; ++j) {
          if (j == start || rng.Uniform() < params.cr) trial(j) = mutant(j);
        }
      }
      for (Eigen::Index j = 0; j < dim; ++j) {
        if (trial(j) < lo(j)) trial(j) = 0.5 * (base(j) + lo(j));
        if (trial(j) > hi(j)) trial(j) = 0.5 * (base(j) + hi(j));
      }
      trials.col(i) = trial;
    }
    problem.Evaluate(trials, trial_fitness);
    result.evaluations += params.population;
    for (Eigen::Index i = 0; i < np; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      if (trial_fitness[ui] <= pop.fitness[ui]) {
        pop.x.col(i) = trials.col(i);
        pop.fitness[ui] = trial_fitness[ui];
      }
    }
    result.generations = gen + 1;
  }
  const std::size_t best = pop.BestIndex();
  result.best = pop.x.col(static_cast<Eigen::Index>(best));
  result.best_fitness = pop.fitness[best];
  return result;
}

}  // namespace evoslam
