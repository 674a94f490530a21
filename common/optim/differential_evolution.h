#ifndef EVOSLAM_COMMON_OPTIM_DIFFERENTIAL_EVOLUTION_H_
#define EVOSLAM_COMMON_OPTIM_DIFFERENTIAL_EVOLUTION_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "common/optim/algorithm.h"
#include "common/util/random.h"

namespace evoslam {

// The ten classic strategies of Storn and Price: base vector and number of difference vectors,
// with binomial or exponential crossover.
enum class DeStrategy {
  kRand1Bin,
  kRand1Exp,
  kBest1Bin,
  kBest1Exp,
  kRandToBest1Bin,
  kRandToBest1Exp,
  kBest2Bin,
  kBest2Exp,
  kRand2Bin,
  kRand2Exp,
};

// Names as on the command line: "rand1bin", "rand1exp", "best1bin", ..., "randtobest1exp".
DeStrategy ParseDeStrategy(std::string_view name);  // throws Error listing the valid names
std::string_view DeStrategyName(DeStrategy strategy);
std::vector<std::string> DeStrategyNames();

// Defaults are the settings of the papers' localization experiments (DE/rand/1/exp, 25
// individuals, F 0.6, CR 0.9; 000 and 003 run it for 25 generations).
struct DeParams {
  DeStrategy strategy = DeStrategy::kRand1Exp;
  std::size_t population = 25;
  double f = 0.6;
  double cr = 0.9;
};

// Throws Error naming the parameter that cannot work.
void ValidateDeParams(const DeParams& params);

// Synchronous DE: each generation builds all trial vectors, evaluates them as one batch, then
// keeps each trial that is no worse than its target. Trial coordinates that leave the box are
// put halfway between the violated bound and a point known to lie inside: the best individual for
// the best/* strategies, the target otherwise. The search stays in the window without piling up
// on its edges.
class DifferentialEvolution : public Algorithm {
 public:
  explicit DifferentialEvolution(const DeParams& params);
  std::string_view name() const override { return "de"; }
  const DeParams& params() const { return params_; }

 protected:
  void DoStep(const Problem& problem, Rng& rng) override;
  std::size_t PopulationSize() const override { return params_.population; }

 private:
  DeParams params_;
  Eigen::MatrixXd trials_;
  Eigen::MatrixXd trial_f_;
  Eigen::VectorXd mutant_;
};

// Builds the trial vector for target i of population x: the strategy's mutant (written to
// `mutant`), crossed over with x_i, pulled back into the box and conformed to the encoding.
void BuildDeTrial(const Problem& problem, DeStrategy strategy, const Eigen::MatrixXd& x,
                  std::size_t i, std::size_t best, double f, double cr, Rng& rng,
                  Eigen::VectorXd& mutant, Eigen::Ref<Eigen::VectorXd> trial);

// How many random population members a strategy's mutant uses besides the target and the best.
std::size_t DeRandomMembers(DeStrategy strategy);
bool DeIsExponential(DeStrategy strategy);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_DIFFERENTIAL_EVOLUTION_H_
