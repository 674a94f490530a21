#ifndef EVOSLAM_COMMON_OPTIM_MU_PLUS_LAMBDA_H_
#define EVOSLAM_COMMON_OPTIM_MU_PLUS_LAMBDA_H_

#include <cstddef>
#include <string_view>

#include "common/optim/algorithm.h"

namespace evoslam {

// Defaults are the global search settings of paper 002 (section 3.2 and its experiments). The
// chromosome there is L columns of three (error, mean) pairs, one pair per axis x, y, theta:
// gene_group 2 keeps a pair together, column 6 is one chromosome column. A problem that is not
// such a chromosome should use gene_group 1 and column 1 (every gene is its own column). When the
// dimension is not a multiple of `column` the last column is shorter, and likewise the last
// group of a column.
struct MuPlusLambdaParams {
  std::size_t mu = 10;
  std::size_t lambda = 70;
  std::size_t q = 5;  // tournament size of survivor selection
  double pc = 0.8;    // crossover probability per pair of parents
  double pm = 0.05;   // mutation probability per column of each child
  double c = 0.1;     // mutation step as a fraction of the gene's largest magnitude
  std::size_t gene_group = 2;
  std::size_t column = 6;
  // The run length that splits crossover into its single-gene first half and its whole-group
  // second half; normally the stop criteria's generation limit.
  std::size_t generation_limit = 100;
  // Share of the mu survivors taken from the offspring (002: 80 %), rounded to a whole number.
  double offspring_share = 0.8;
  // Converged() once every objective's variance over the population (divided by mu) is below
  // this; 0 turns it off. 002 gives no value; 1e-12 stops only a population that has collapsed
  // onto (nearly) one fitness.
  double variance_threshold = 1e-12;
};

// Throws Error naming the parameter that cannot work.
void ValidateMuPlusLambdaParams(const MuPlusLambdaParams& params);

// How many of the mu survivors come from the offspring.
std::size_t OffspringSurvivors(const MuPlusLambdaParams& params);

// The (mu + lambda) evolutionary algorithm of paper 002's global search, for one or more
// objectives. Each generation:
//  - lambda children come from pairs of distinct parents drawn at random; with probability pc a
//    pair is combined by uniform crossover into two complementary children (each unit from one
//    parent or the other with probability 1/2; a unit is one gene while 2 * generation <
//    generation_limit, one gene group from then on, also past the limit), otherwise the children
//    copy their parents; an odd lambda drops the second child of the last pair;
//  - each column of each child mutates with probability pm: one of its gene groups is picked,
//    then one gene of that group, and a uniform number in [-c s, c s] is added, s being the
//    largest magnitude of the gene's bounds; a change that would leave the box is dropped, and
//    integer or binary problems see the child rounded afterwards;
//  - parents and children are ranked together (Pareto fronts then crowding; for one objective
//    simply by fitness), and q-tournaments fill the new population: offspring_share of mu from
//    the children, the rest from the parents. A tournament draws min(q, pool size) distinct
//    contestants, and its winner leaves the pool so it is not drawn again.
// Survivor selection is therefore not strictly elitist: the best individual survives only if it
// takes part in a tournament (the champion is kept apart by Algorithm all the same).
class MuPlusLambdaEa : public Algorithm {
 public:
  explicit MuPlusLambdaEa(const MuPlusLambdaParams& params);
  std::string_view name() const override { return "mu+lambda"; }
  bool multi_objective() const override { return true; }
  const MuPlusLambdaParams& params() const { return params_; }

  // 002's second stopping rule: the variance of fitness has fallen below the threshold.
  bool Converged() const override;

 protected:
  void DoStep(const Problem& problem, Rng& rng) override;
  std::size_t PopulationSize() const override { return params_.mu; }

 private:
  MuPlusLambdaParams params_;
  Eigen::MatrixXd offspring_;
  Eigen::MatrixXd offspring_f_;
  Eigen::MatrixXd union_f_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_MU_PLUS_LAMBDA_H_
