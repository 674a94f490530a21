#ifndef EVOSLAM_COMMON_OPTIM_SELF_ADAPTIVE_DE_H_
#define EVOSLAM_COMMON_OPTIM_SELF_ADAPTIVE_DE_H_

#include <cstddef>
#include <string_view>

#include "common/optim/algorithm.h"
#include "common/optim/differential_evolution.h"

namespace evoslam {

// jDE (Brest, Greiner, Boskovic, Mernik and Zumer 2006): every individual carries its own F and
// CR. Before its trial vector is built, F is redrawn from [f_lower, f_lower + f_range) with
// probability tau_f and CR from [0, 1) with probability tau_cr; the new values survive only if
// the trial does. Defaults are the paper's.
struct JdeParams {
  DeStrategy strategy = DeStrategy::kRand1Bin;
  std::size_t population = 25;
  double tau_f = 0.1;
  double tau_cr = 0.1;
  double f_lower = 0.1;
  double f_range = 0.9;
  double f_initial = 0.5;
  double cr_initial = 0.9;
};

void ValidateJdeParams(const JdeParams& params);

class SelfAdaptiveDe : public Algorithm {
 public:
  explicit SelfAdaptiveDe(const JdeParams& params);
  std::string_view name() const override { return "jde"; }
  const JdeParams& params() const { return params_; }

  void Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
               const Eigen::Ref<const Eigen::VectorXd>& f) override;

 protected:
  void DoInitialize(const Problem& problem, Rng& rng) override;
  void DoStep(const Problem& problem, Rng& rng) override;
  std::size_t PopulationSize() const override { return params_.population; }
  void SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const override;
  void RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) override;

 private:
  JdeParams params_;
  // Row 0: F, row 1: CR, one column per individual.
  Eigen::MatrixXd control_;
  Eigen::MatrixXd trials_;
  Eigen::MatrixXd trial_f_;
  Eigen::MatrixXd trial_control_;
  Eigen::VectorXd mutant_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_SELF_ADAPTIVE_DE_H_
