#include "common/optim/differential_evolution.h"

#include <algorithm>
#include <array>

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

// Writes the strategy's mutant for target i into `out`; returns the index of the individual that
// out-of-box coordinates are pulled back towards (the best for best/*, the target otherwise).
std::size_t Mutant(DeStrategy s, const Eigen::MatrixXd& pop, std::size_t i, std::size_t best,
                   double f, Rng& rng, Eigen::VectorXd& out) {
  const std::size_t n = static_cast<std::size_t>(pop.cols());
  const auto r = DistinctIndices(DeRandomMembers(s), n, i, rng);
  const auto x = [&](std::size_t k) { return pop.col(static_cast<Eigen::Index>(k)); };
  switch (s) {
    case DeStrategy::kRand1Bin:
    case DeStrategy::kRand1Exp:
      out = x(r[0]) + f * (x(r[1]) - x(r[2]));
      return i;
    case DeStrategy::kBest1Bin:
    case DeStrategy::kBest1Exp:
      out = x(best) + f * (x(r[0]) - x(r[1]));
      return best;
    case DeStrategy::kRandToBest1Bin:
    case DeStrategy::kRandToBest1Exp:
      out = x(i) + f * (x(best) - x(i)) + f * (x(r[0]) - x(r[1]));
      return i;
    case DeStrategy::kBest2Bin:
    case DeStrategy::kBest2Exp:
      out = x(best) + f * (x(r[0]) + x(r[1]) - x(r[2]) - x(r[3]));
      return best;
    case DeStrategy::kRand2Bin:
    case DeStrategy::kRand2Exp:
      out = x(r[4]) + f * (x(r[0]) + x(r[1]) - x(r[2]) - x(r[3]));
      return i;
  }
  throw Error("differential evolution: unknown strategy");
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

bool DeIsExponential(DeStrategy s) {
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

std::size_t DeRandomMembers(DeStrategy s) {
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

void ValidateDeParams(const DeParams& params) {
  const std::size_t needed = DeRandomMembers(params.strategy) + 1;
  if (params.population < needed) {
    throw Error("differential evolution: population " + std::to_string(params.population) +
                " is too small for strategy " + std::string(DeStrategyName(params.strategy)) +
                " (needs at least " + std::to_string(needed) + ")");
  }
  if (!(params.f > 0.0 && params.f <= 2.0))
    throw Error("differential evolution: F must be in (0, 2]");
  if (!(params.cr >= 0.0 && params.cr <= 1.0))
    throw Error("differential evolution: CR must be in [0, 1]");
}

DifferentialEvolution::DifferentialEvolution(const DeParams& params) : params_(params) {
  ValidateDeParams(params_);
}

void BuildDeTrial(const Problem& problem, DeStrategy strategy, const Eigen::MatrixXd& x,
                  std::size_t i, std::size_t best, double f, double cr, Rng& rng,
                  Eigen::VectorXd& mutant, Eigen::Ref<Eigen::VectorXd> trial) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const Eigen::Index dim = x.rows();
  const auto base = static_cast<Eigen::Index>(Mutant(strategy, x, i, best, f, rng, mutant));
  trial = x.col(static_cast<Eigen::Index>(i));
  const Eigen::Index start =
      static_cast<Eigen::Index>(rng.UniformIndex(static_cast<std::size_t>(dim)));
  if (DeIsExponential(strategy)) {
    // A run of consecutive genes, starting at a random one, continued while rand < CR.
    Eigen::Index len = 0;
    do {
      const Eigen::Index j = (start + len) % dim;
      trial(j) = mutant(j);
      ++len;
    } while (len < dim && rng.Uniform() < cr);
  } else {
    for (Eigen::Index j = 0; j < dim; ++j) {
      if (j == start || rng.Uniform() < cr) trial(j) = mutant(j);
    }
  }
  for (Eigen::Index j = 0; j < dim; ++j) {
    if (trial(j) < lo(j)) trial(j) = 0.5 * (x(j, base) + lo(j));
    if (trial(j) > hi(j)) trial(j) = 0.5 * (x(j, base) + hi(j));
  }
  if (problem.encoding() != Encoding::kReal) Conform(problem, trial);
}

void DifferentialEvolution::DoStep(const Problem& problem, Rng& rng) {
  const Eigen::MatrixXd& x = population_.x;
  trials_.resize(x.rows(), x.cols());
  const std::size_t best = population_.BestIndex();
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    BuildDeTrial(problem, params_.strategy, x, static_cast<std::size_t>(i), best, params_.f,
                 params_.cr, rng, mutant_, trials_.col(i));
  }
  Evaluate(problem, trials_, trial_f_);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    if (trial_f_(0, i) <= population_.f(0, i)) {
      population_.x.col(i) = trials_.col(i);
      population_.f.col(i) = trial_f_.col(i);
    }
  }
}

}  // namespace evoslam
