#include "common/optim/algorithm.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/util/error.h"

namespace evoslam {

void Algorithm::Initialize(const Problem& problem, Rng& rng) {
  ValidateProblem(problem);
  if (problem.objectives() != 1 && !multi_objective()) {
    throw Error(std::string(name()) + " optimises one objective; the problem has " +
                std::to_string(problem.objectives()));
  }
  generation_ = 0;
  evaluations_ = 0;
  champion_x_.resize(0);
  champion_f_.resize(0);
  DoInitialize(problem, rng);
}

void Algorithm::Step(const Problem& problem, Rng& rng) {
  if (population_.size() == 0) throw Error(std::string(name()) + ": Step before Initialize");
  DoStep(problem, rng);
  ++generation_;
}

void Algorithm::Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
                        const Eigen::Ref<const Eigen::VectorXd>& f) {
  const auto i = static_cast<Eigen::Index>(index);
  population_.x.col(i) = x;
  population_.f.col(i) = f;
}

AlgorithmState Algorithm::Save() const {
  AlgorithmState state;
  state.population = population_;
  SaveMemory(state.memory);
  state.generation = generation_;
  state.evaluations = evaluations_;
  state.champion_x = champion_x_;
  state.champion_f = champion_f_;
  return state;
}

void Algorithm::Restore(const AlgorithmState& state) {
  if (state.population.size() != PopulationSize()) {
    throw Error(std::string(name()) + ": checkpoint holds " +
                std::to_string(state.population.size()) + " individuals, the parameters ask for " +
                std::to_string(PopulationSize()));
  }
  if (state.population.f.cols() != state.population.x.cols())
    throw Error(std::string(name()) + ": checkpoint fitness does not match its population");
  population_ = state.population;
  RestoreMemory(state.memory);
  generation_ = state.generation;
  evaluations_ = state.evaluations;
  champion_x_ = state.champion_x;
  champion_f_ = state.champion_f;
}

void Algorithm::DoInitialize(const Problem& problem, Rng& rng) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  Eigen::MatrixXd x(lo.size(), static_cast<Eigen::Index>(PopulationSize()));
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (Eigen::Index j = 0; j < x.rows(); ++j) x(j, i) = rng.Uniform(lo(j), hi(j));
    Conform(problem, x.col(i));
  }
  const std::vector<Eigen::VectorXd> starts = problem.starts();
  for (Eigen::Index i = 0; i < std::min<Eigen::Index>(x.cols(), std::ssize(starts)); ++i) {
    const Eigen::VectorXd& start = starts[static_cast<std::size_t>(i)];
    if (start.size() != x.rows())
      throw Error(std::string(name()) + ": start " + std::to_string(i) + " has the wrong size");
    x.col(i) = start;
    Conform(problem, x.col(i));
  }
  population_.x = std::move(x);
  Evaluate(problem, population_.x, population_.f);
}

void Algorithm::Evaluate(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& x,
                         Eigen::MatrixXd& f) {
  EvaluateBatch(problem, x, f);
  evaluations_ += static_cast<std::size_t>(x.cols());
  if (f.rows() == 1) UpdateChampion(x, f);
}

void Algorithm::UpdateChampion(const Eigen::Ref<const Eigen::MatrixXd>& x,
                               const Eigen::MatrixXd& f) {
  for (Eigen::Index i = 0; i < f.cols(); ++i) {
    // NaN never becomes the champion: the comparison is false.
    if (champion_f_.size() == 0 ? !std::isnan(f(0, i)) : f(0, i) < champion_f_(0)) {
      champion_x_ = x.col(i);
      champion_f_ = f.col(i);
    }
  }
}

const Eigen::MatrixXd& MemoryEntry(const std::map<std::string, Eigen::MatrixXd>& memory,
                                   const std::string& name, Eigen::Index rows, Eigen::Index cols) {
  const auto it = memory.find(name);
  if (it == memory.end()) throw Error("checkpoint lacks the algorithm memory '" + name + "'");
  if (it->second.rows() != rows || it->second.cols() != cols) {
    throw Error("checkpoint memory '" + name + "' is " + std::to_string(it->second.rows()) + "x" +
                std::to_string(it->second.cols()) + ", expected " + std::to_string(rows) + "x" +
                std::to_string(cols));
  }
  return it->second;
}

}  // namespace evoslam
