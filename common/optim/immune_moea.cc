#include "common/optim/immune_moea.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/optim/immunity.h"
#include "common/optim/pareto.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {

ImmuneRecombination ParseImmuneRecombination(std::string_view name) {
  if (name == "blend") return ImmuneRecombination::kBlend;
  if (name == "uniform") return ImmuneRecombination::kUniform;
  throw Error("unknown recombination '" + std::string(name) + "' (expected blend or uniform)");
}

std::string_view ImmuneRecombinationName(ImmuneRecombination recombination) {
  return recombination == ImmuneRecombination::kBlend ? "blend" : "uniform";
}
namespace {

Population Join(const Population& a, const Population& b) {
  Population joined;
  joined.x.resize(a.x.rows(), a.x.cols() + b.x.cols());
  joined.f.resize(a.f.rows(), a.f.cols() + b.f.cols());
  joined.x << a.x, b.x;
  joined.f << a.f, b.f;
  return joined;
}

Population Columns(const Population& from, const std::vector<std::size_t>& indices) {
  Population out;
  out.x.resize(from.x.rows(), static_cast<Eigen::Index>(indices.size()));
  out.f.resize(from.f.rows(), static_cast<Eigen::Index>(indices.size()));
  for (std::size_t i = 0; i < indices.size(); ++i) {
    out.x.col(static_cast<Eigen::Index>(i)) = from.x.col(static_cast<Eigen::Index>(indices[i]));
    out.f.col(static_cast<Eigen::Index>(i)) = from.f.col(static_cast<Eigen::Index>(indices[i]));
  }
  return out;
}

// The best `count` members by the Pareto order (all of them when there are fewer).
Population Best(const Population& from, std::size_t count) {
  std::vector<std::size_t> order = RankPareto(from.f).Order();
  order.resize(std::min(count, order.size()));
  return Columns(from, order);
}

std::size_t BinaryTournament(const ParetoRanking& ranking, Rng& rng) {
  const std::size_t a = rng.UniformIndex(ranking.size());
  const std::size_t b = rng.UniformIndex(ranking.size());
  return ranking.Before(b, a) ? b : a;
}

void Recombine(const ImmuneMoeaParams& params, const Eigen::Ref<const Eigen::VectorXd>& a,
               const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> child,
               Rng& rng) {
  for (Eigen::Index j = 0; j < child.size(); ++j) {
    if (params.recombination == ImmuneRecombination::kUniform) {
      child(j) = rng.Uniform() < 0.5 ? a(j) : b(j);
      continue;
    }
    const double lo = std::min(a(j), b(j));
    const double hi = std::max(a(j), b(j));
    const double widen = params.blend_alpha * (hi - lo);
    child(j) = rng.Uniform(lo - widen, hi + widen);
  }
}

}  // namespace

void ValidateImmuneMoeaParams(const ImmuneMoeaParams& params) {
  const std::string name = "immune MOEA: ";
  if (params.population < 2) throw Error(name + "population must be at least 2");
  if (params.recombinations + params.mutations == 0)
    throw Error(name + "recombinations and mutations are both 0, so no candidate is ever made");
  const auto probability = [&](double p, const char* what) {
    if (!(p >= 0.0 && p <= 1.0)) throw Error(name + what + " must be in [0, 1]");
  };
  probability(params.p_recombination, "p_recombination");
  probability(params.p_immunity, "p_immunity");
  probability(params.p_mutation, "p_mutation");
  if (!IsFiniteNonNegative(params.blend_alpha))
    throw Error(name + "blend_alpha must be a finite number >= 0");
  if (!(params.restart_spread >= 0.0 && params.restart_spread <= 1.0))
    throw Error(name + "restart_spread must be in [0, 1]");
  if (params.archive_size < 1) throw Error(name + "archive_size must be at least 1");
}

ImmuneMoea::ImmuneMoea(const ImmuneMoeaParams& params) : params_(params) {
  ValidateImmuneMoeaParams(params_);
}

Population ImmuneMoea::Front() const {
  const Population all = Join(population_, archive_);
  return Columns(all, FirstFront(all.f));
}

bool ImmuneMoea::PopulationConverged(const Problem& problem) const {
  const Eigen::VectorXd width = problem.upper() - problem.lower();
  const Eigen::VectorXd spread =
      population_.x.rowwise().maxCoeff() - population_.x.rowwise().minCoeff();
  bool searched = false;  // a box of zero width everywhere has nothing to restart
  for (Eigen::Index j = 0; j < width.size(); ++j) {
    if (!(width(j) > 0.0)) continue;
    searched = true;
    if (!(spread(j) < params_.restart_spread * width(j))) return false;
  }
  return searched;
}

void ImmuneMoea::DoInitialize(const Problem& problem, Rng& rng) {
  Algorithm::DoInitialize(problem, rng);
  archive_.x.resize(population_.x.rows(), 0);
  archive_.f.resize(population_.f.rows(), 0);
  restarts_ = 0;
}

void ImmuneMoea::DoStep(const Problem& problem, Rng& rng) {
  if (PopulationConverged(problem)) {
    Restart(problem, rng);
  } else {
    Generation(problem, rng);
  }
}

void ImmuneMoea::Restart(const Problem& problem, Rng& rng) {
  const Population joined = Join(archive_, population_);
  archive_ = Best(Columns(joined, FirstFront(joined.f)), params_.archive_size);
  Algorithm::DoInitialize(problem, rng);
  ++restarts_;
}

void ImmuneMoea::Generation(const Problem& problem, Rng& rng) {
  const Population pool = Join(population_, archive_);
  const ParetoRanking ranking = RankPareto(pool.f);
  const Immunity* immunity = problem.immunity();
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const Eigen::Index dim = pool.x.rows();

  Eigen::MatrixXd children(dim,
                           static_cast<Eigen::Index>(params_.recombinations + params_.mutations));
  Eigen::Index made = 0;
  Eigen::VectorXd child(dim);
  Eigen::VectorXd vaccinated(dim);
  // Vaccination and immune selection, then the child joins the batch unless it is a copy.
  const auto finish = [&](const Eigen::Ref<const Eigen::VectorXd>& source) {
    Conform(problem, child);
    if (immunity != nullptr && rng.Uniform() < params_.p_immunity) {
      vaccinated = child;
      if (immunity->Vaccinate(vaccinated, rng)) {
        Conform(problem, vaccinated);
        if (immunity->Accept(child, vaccinated, rng)) child = vaccinated;
      }
    }
    if (child != source) children.col(made++) = child;
  };
  for (std::size_t r = 0; r < params_.recombinations; ++r) {
    const auto a = static_cast<Eigen::Index>(BinaryTournament(ranking, rng));
    const auto b = static_cast<Eigen::Index>(BinaryTournament(ranking, rng));
    child = pool.x.col(a);
    if (rng.Uniform() < params_.p_recombination)
      Recombine(params_, pool.x.col(a), pool.x.col(b), child, rng);
    finish(pool.x.col(a));
  }
  for (std::size_t m = 0; m < params_.mutations; ++m) {
    const auto source = static_cast<Eigen::Index>(rng.UniformIndex(params_.population));
    child = population_.x.col(source);
    for (Eigen::Index j = 0; j < dim; ++j) {
      if (rng.Uniform() < params_.p_mutation) child(j) = rng.Uniform(lo(j), hi(j));
    }
    finish(population_.x.col(source));
  }
  if (made == 0) return;

  Population offspring;
  offspring.x = children.leftCols(made);
  Evaluate(problem, offspring.x, offspring.f);
  population_ = Best(Join(population_, offspring), params_.population);
}

void ImmuneMoea::SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const {
  memory["archive_x"] = archive_.x;
  memory["archive_f"] = archive_.f;
  memory["restarts"] = Eigen::MatrixXd::Constant(1, 1, static_cast<double>(restarts_));
}

void ImmuneMoea::RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) {
  const auto entry = [&](const std::string& name) -> const Eigen::MatrixXd& {
    const auto it = memory.find(name);
    if (it == memory.end()) throw Error("checkpoint lacks the algorithm memory '" + name + "'");
    return it->second;
  };
  const Eigen::MatrixXd& x = entry("archive_x");
  const Eigen::MatrixXd& f = entry("archive_f");
  if (x.rows() != population_.x.rows() || f.rows() != population_.f.rows() ||
      x.cols() != f.cols() || static_cast<std::size_t>(x.cols()) > params_.archive_size) {
    throw Error("checkpoint archive is " + std::to_string(x.rows()) + "x" +
                std::to_string(x.cols()) + " with fitness " + std::to_string(f.rows()) + "x" +
                std::to_string(f.cols()) + ", which does not fit this problem and archive_size " +
                std::to_string(params_.archive_size));
  }
  archive_.x = x;
  archive_.f = f;
  restarts_ = static_cast<std::size_t>(MemoryEntry(memory, "restarts", 1, 1)(0, 0));
}

}  // namespace evoslam
