#ifndef EVOSLAM_COMMON_OPTIM_IMMUNE_MOEA_H_
#define EVOSLAM_COMMON_OPTIM_IMMUNE_MOEA_H_

#include <cstddef>
#include <string_view>

#include "common/optim/algorithm.h"

namespace evoslam {

// How two parents make the one child of a recombination.
enum class ImmuneRecombination {
  // BLX-alpha: each gene uniform in the parents' interval widened by alpha times its length on
  // both sides, then clipped to the box. It explores beyond the parents without a separate
  // mutation, which 004 applies only to its own candidates.
  kBlend,
  // Each gene from one parent or the other with probability 1/2.
  kUniform,
};
ImmuneRecombination ParseImmuneRecombination(std::string_view name);  // "blend" | "uniform"
std::string_view ImmuneRecombinationName(ImmuneRecombination recombination);

// Defaults: population, p_R, p_I and p_M are 004's (section 4: 50, 0.9, 0.3, 0.08); the rest
// are evoslam's choices where 004 is silent (see docs/multi_objective.md).
struct ImmuneMoeaParams {
  std::size_t population = 50;
  // Children per generation made by recombination and by mutation: 50 new candidates a
  // generation, like NSGA-II's, most of them from recombination as 004's p_R >> p_M suggests.
  std::size_t recombinations = 40;
  std::size_t mutations = 10;
  double p_recombination = 0.9;
  double p_immunity = 0.3;   // probability of vaccinating a new candidate
  double p_mutation = 0.08;  // per gene: reset uniformly in its range
  ImmuneRecombination recombination = ImmuneRecombination::kBlend;
  double blend_alpha = 0.5;
  // The population has converged, and is replaced by a random one, when along every coordinate
  // it spans less than this fraction of the box; 0 turns restarts off.
  double restart_spread = 0.01;
  // Most members the archive of converged fronts keeps; the most crowded go first.
  std::size_t archive_size = 50;
};

// Throws Error naming the parameter that cannot work.
void ValidateImmuneMoeaParams(const ImmuneMoeaParams& params);

// The multi-objective EA with immunity of paper 004 (section 3.1). Each generation:
//  - `recombinations` children: two parents from P u G by binary tournament on the Pareto order,
//    recombined with probability p_recombination (else the child copies the first parent);
//  - `mutations` children: a member of P drawn uniformly, each gene reset with p_mutation;
//  - every child is vaccinated with probability p_immunity when the problem has an Immunity,
//    and immune selection (Immunity::Accept) keeps the vaccinated or the original child;
//  - the children that differ from the member they came from are evaluated as one batch (an
//    unchanged copy would cost an evaluation and add nothing), and P becomes the best
//    `population` of P and the children by the Pareto order (fronts, then crowding).
// 004 replaces a converged P by a fresh random one. Here a generation that finds P converged
// (see restart_spread) is spent on that restart instead: the first front of G u P becomes the
// archive G, and a random P is drawn and evaluated. G then takes part in parent selection, and
// with P makes up the result (Front), so a restart never loses the front found so far. Before
// the first restart G is empty, as in 004's pseudocode. G does not compete for places in P (its
// members would then be in P and G at once and count twice as parents); its own renewal at each
// restart is the survivor selection it takes part in. Converged() stays false, since a
// converged population restarts instead of ending the run; the stop criteria's stagnation
// limit (004's "N generations without improvement") watches P.
class ImmuneMoea : public Algorithm {
 public:
  explicit ImmuneMoea(const ImmuneMoeaParams& params);
  std::string_view name() const override { return "immune"; }
  bool multi_objective() const override { return true; }
  const ImmuneMoeaParams& params() const { return params_; }

  // G: the fronts of the populations that converged (empty before the first restart).
  const Population& archive() const { return archive_; }
  std::size_t restarts() const { return restarts_; }
  // The first front of P u G: the run's result.
  Population Front() const;
  // Whether P spans less than restart_spread of the box along every coordinate.
  bool PopulationConverged(const Problem& problem) const;

 protected:
  void DoInitialize(const Problem& problem, Rng& rng) override;
  void DoStep(const Problem& problem, Rng& rng) override;
  std::size_t PopulationSize() const override { return params_.population; }
  void SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const override;
  void RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) override;

 private:
  void Restart(const Problem& problem, Rng& rng);
  void Generation(const Problem& problem, Rng& rng);

  ImmuneMoeaParams params_;
  Population archive_;
  std::size_t restarts_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_IMMUNE_MOEA_H_
