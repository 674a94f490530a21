#ifndef EVOSLAM_COMMON_OPTIM_ALGORITHM_H_
#define EVOSLAM_COMMON_OPTIM_ALGORITHM_H_

#include <cstddef>
#include <map>
#include <string>
#include <string_view>

#include "common/optim/population.h"
#include "common/optim/problem.h"
#include "common/util/random.h"

namespace evoslam {

// Everything an algorithm instance needs to continue a run bit for bit, apart from its parameters
// (held by whoever built it) and its random generator (passed to every call). `memory` holds what
// is particular to one algorithm, under names it chooses: PSO velocities and personal bests, jDE's
// adaptive F and CR, the aGA's dormant chromosomes.
struct AlgorithmState {
  Population population;
  std::map<std::string, Eigen::MatrixXd> memory;
  std::size_t generation = 0;
  std::size_t evaluations = 0;
  // The best candidate ever evaluated (single-objective problems; empty otherwise).
  Eigen::VectorXd champion_x;
  Eigen::VectorXd champion_f;
};

// A population-based optimiser, advanced one generation at a time. Every random draw comes from
// the generator passed in, so a run is a function of the problem, the parameters and the
// generator's state; every candidate is evaluated through Evaluate, one batch per call.
class Algorithm {
 public:
  virtual ~Algorithm() = default;

  virtual std::string_view name() const = 0;
  // Whether the algorithm ranks candidates by Pareto dominance; the others need one objective.
  virtual bool multi_objective() const { return false; }

  // Draws and evaluates the first population and resets the counters. Throws Error when the
  // parameters cannot work on this problem (too few individuals, wrong number of objectives).
  void Initialize(const Problem& problem, Rng& rng);
  // One generation.
  void Step(const Problem& problem, Rng& rng);

  // The individuals other islands see and replace.
  const Population& population() const { return population_; }
  // Puts an immigrant in place of member `index`; algorithms keep their memory consistent.
  virtual void Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const Eigen::VectorXd>& f);

  std::size_t generation() const { return generation_; }
  std::size_t evaluations() const { return evaluations_; }
  // The best candidate ever evaluated, for single-objective problems (empty before Initialize).
  const Eigen::VectorXd& champion_x() const { return champion_x_; }
  const Eigen::VectorXd& champion_f() const { return champion_f_; }

  // The algorithm's own stopping rule (002: the variance of fitness has fallen below a
  // threshold); false for algorithms without one.
  virtual bool Converged() const { return false; }

  AlgorithmState Save() const;
  // Continues from a state saved by an instance with the same parameters on the same problem.
  void Restore(const AlgorithmState& state);

 protected:
  // Default: a uniform random population of PopulationSize() individuals.
  virtual void DoInitialize(const Problem& problem, Rng& rng);
  virtual void DoStep(const Problem& problem, Rng& rng) = 0;
  virtual std::size_t PopulationSize() const = 0;
  virtual void SaveMemory(std::map<std::string, Eigen::MatrixXd>& /*memory*/) const {}
  // Throws Error when an entry is missing or of the wrong shape.
  virtual void RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& /*memory*/) {}

  // Evaluates a batch, counts it and keeps the champion up to date.
  void Evaluate(const Problem& problem, const Eigen::Ref<const Eigen::MatrixXd>& x,
                Eigen::MatrixXd& f);

  Population population_;

 private:
  void UpdateChampion(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::MatrixXd& f);

  std::size_t generation_ = 0;
  std::size_t evaluations_ = 0;
  Eigen::VectorXd champion_x_;
  Eigen::VectorXd champion_f_;
};

// Reads memory[name] and checks its shape; throws Error naming the entry otherwise.
const Eigen::MatrixXd& MemoryEntry(const std::map<std::string, Eigen::MatrixXd>& memory,
                                   const std::string& name, Eigen::Index rows, Eigen::Index cols);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_ALGORITHM_H_
