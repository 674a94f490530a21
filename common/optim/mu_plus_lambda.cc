#include "common/optim/mu_plus_lambda.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/optim/pareto.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// Uniform crossover of a and b in place, swapping units of `unit` consecutive genes (the last
// one may be shorter), each with probability 1/2; the two results are complementary.
void UniformCrossover(Eigen::Ref<Eigen::VectorXd> a, Eigen::Ref<Eigen::VectorXd> b,
                      std::size_t unit, Rng& rng) {
  const auto step = static_cast<Eigen::Index>(unit);
  for (Eigen::Index start = 0; start < a.size(); start += step) {
    if (rng.Uniform() >= 0.5) continue;
    const Eigen::Index len = std::min(step, a.size() - start);
    a.segment(start, len).swap(b.segment(start, len));
  }
}

// 002's column mutation; see the class comment.
void MutateColumns(const MuPlusLambdaParams& params, const Problem& problem,
                   Eigen::Ref<Eigen::VectorXd> child, Rng& rng) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const auto column = static_cast<Eigen::Index>(params.column);
  const auto group = static_cast<Eigen::Index>(params.gene_group);
  for (Eigen::Index start = 0; start < child.size(); start += column) {
    if (rng.Uniform() >= params.pm) continue;
    const Eigen::Index len = std::min(column, child.size() - start);
    const Eigen::Index groups = (len + group - 1) / group;
    const Eigen::Index first =
        start +
        group * static_cast<Eigen::Index>(rng.UniformIndex(static_cast<std::size_t>(groups)));
    const Eigen::Index members = std::min(group, start + len - first);
    const Eigen::Index j =
        first + static_cast<Eigen::Index>(rng.UniformIndex(static_cast<std::size_t>(members)));
    const double s = params.c * std::max(std::abs(lo(j)), std::abs(hi(j)));
    const double moved = child(j) + rng.Uniform(-s, s);
    if (moved >= lo(j) && moved <= hi(j)) child(j) = moved;
  }
}

// Appends `count` q-tournament winners drawn from `pool` to `chosen`. Each tournament draws
// min(q, pool size) distinct contestants; its winner leaves the pool.
void Tournaments(const ParetoRanking& ranking, std::size_t q, std::vector<std::size_t> pool,
                 std::size_t count, std::vector<std::size_t>& chosen, Rng& rng) {
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t size = std::min(q, pool.size());
    // A partial Fisher-Yates shuffle puts the contestants in pool[0, size).
    for (std::size_t k = 0; k < size; ++k)
      std::swap(pool[k], pool[k + rng.UniformIndex(pool.size() - k)]);
    std::size_t winner = 0;
    for (std::size_t k = 1; k < size; ++k) {
      if (ranking.Before(pool[k], pool[winner])) winner = k;
    }
    chosen.push_back(pool[winner]);
    pool[winner] = pool.back();
    pool.pop_back();
  }
}

}  // namespace

std::size_t OffspringSurvivors(const MuPlusLambdaParams& params) {
  return static_cast<std::size_t>(
      std::lround(params.offspring_share * static_cast<double>(params.mu)));
}

void ValidateMuPlusLambdaParams(const MuPlusLambdaParams& params) {
  const std::string name = "(mu+lambda) EA: ";
  if (params.mu < 2) throw Error(name + "mu must be at least 2, to draw two distinct parents");
  if (params.lambda < 1) throw Error(name + "lambda must be at least 1");
  if (params.q < 1) throw Error(name + "tournament size q must be at least 1");
  if (!(params.pc >= 0.0 && params.pc <= 1.0)) throw Error(name + "pc must be in [0, 1]");
  if (!(params.pm >= 0.0 && params.pm <= 1.0)) throw Error(name + "pm must be in [0, 1]");
  if (!IsFinitePositive(params.c))
    throw Error(name + "mutation step c must be a finite number > 0");
  if (params.gene_group < 1) throw Error(name + "gene_group must be at least 1");
  if (params.column < 1 || params.column % params.gene_group != 0) {
    throw Error(name + "column (" + std::to_string(params.column) +
                ") must be a positive multiple of gene_group (" +
                std::to_string(params.gene_group) + ")");
  }
  if (params.generation_limit < 1) throw Error(name + "generation_limit must be at least 1");
  if (!(params.offspring_share >= 0.0 && params.offspring_share <= 1.0))
    throw Error(name + "offspring_share must be in [0, 1]");
  if (OffspringSurvivors(params) > params.lambda) {
    throw Error(name + "lambda (" + std::to_string(params.lambda) + ") is smaller than the " +
                std::to_string(OffspringSurvivors(params)) + " survivors it must supply");
  }
  if (!IsFiniteNonNegative(params.variance_threshold))
    throw Error(name + "variance_threshold must be a finite number >= 0");
}

MuPlusLambdaEa::MuPlusLambdaEa(const MuPlusLambdaParams& params) : params_(params) {
  ValidateMuPlusLambdaParams(params_);
}

bool MuPlusLambdaEa::Converged() const {
  const Eigen::MatrixXd& f = population_.f;
  if (f.cols() == 0) return false;
  for (Eigen::Index k = 0; k < f.rows(); ++k) {
    const double variance = (f.row(k).array() - f.row(k).mean()).square().mean();
    // NaN fails the comparison, so a population with a failed evaluation has not converged.
    if (!(variance < params_.variance_threshold)) return false;
  }
  return true;
}

void MuPlusLambdaEa::DoStep(const Problem& problem, Rng& rng) {
  const Eigen::MatrixXd& x = population_.x;
  const auto mu = static_cast<Eigen::Index>(params_.mu);
  const auto lambda = static_cast<Eigen::Index>(params_.lambda);
  const std::size_t unit = 2 * generation() < params_.generation_limit ? 1 : params_.gene_group;

  // Children come in pairs; an odd lambda drops the second child of the last pair.
  offspring_.resize(x.rows(), lambda + lambda % 2);
  for (Eigen::Index k = 0; k < offspring_.cols(); k += 2) {
    const std::size_t a = rng.UniformIndex(params_.mu);
    std::size_t b = rng.UniformIndex(params_.mu - 1);
    if (b >= a) ++b;
    offspring_.col(k) = x.col(static_cast<Eigen::Index>(a));
    offspring_.col(k + 1) = x.col(static_cast<Eigen::Index>(b));
    if (rng.Uniform() < params_.pc)
      UniformCrossover(offspring_.col(k), offspring_.col(k + 1), unit, rng);
  }
  offspring_.conservativeResize(Eigen::NoChange, lambda);
  for (Eigen::Index k = 0; k < lambda; ++k) {
    MutateColumns(params_, problem, offspring_.col(k), rng);
    if (problem.encoding() != Encoding::kReal) Conform(problem, offspring_.col(k));
  }
  Evaluate(problem, offspring_, offspring_f_);

  // Parents are 0..mu-1 of the ranked union, children mu..mu+lambda-1.
  union_f_.resize(population_.f.rows(), mu + lambda);
  union_f_ << population_.f, offspring_f_;
  const ParetoRanking ranking = RankPareto(union_f_);
  std::vector<std::size_t> children(params_.lambda);
  std::vector<std::size_t> parents(params_.mu);
  for (std::size_t i = 0; i < params_.lambda; ++i) children[i] = params_.mu + i;
  for (std::size_t i = 0; i < params_.mu; ++i) parents[i] = i;
  const std::size_t from_children = OffspringSurvivors(params_);
  std::vector<std::size_t> chosen;
  chosen.reserve(params_.mu);
  Tournaments(ranking, params_.q, std::move(children), from_children, chosen, rng);
  Tournaments(ranking, params_.q, std::move(parents), params_.mu - from_children, chosen, rng);

  Population next;
  next.x.resize(x.rows(), mu);
  next.f.resize(union_f_.rows(), mu);
  for (Eigen::Index i = 0; i < mu; ++i) {
    const auto u = static_cast<Eigen::Index>(chosen[static_cast<std::size_t>(i)]);
    if (u < mu) {
      next.x.col(i) = x.col(u);
    } else {
      next.x.col(i) = offspring_.col(u - mu);
    }
    next.f.col(i) = union_f_.col(u);
  }
  population_ = std::move(next);
}

}  // namespace evoslam
