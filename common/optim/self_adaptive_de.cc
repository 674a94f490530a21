#include "common/optim/self_adaptive_de.h"

#include <string>

#include "common/util/error.h"

namespace evoslam {

void ValidateJdeParams(const JdeParams& params) {
  DeParams de;
  de.strategy = params.strategy;
  de.population = params.population;
  de.f = params.f_initial;
  de.cr = params.cr_initial;
  ValidateDeParams(de);
  if (!(params.tau_f >= 0.0 && params.tau_f <= 1.0) ||
      !(params.tau_cr >= 0.0 && params.tau_cr <= 1.0))
    throw Error("jDE: tau_f and tau_cr are probabilities, in [0, 1]");
  if (!(params.f_lower > 0.0) || !(params.f_range >= 0.0) || params.f_lower + params.f_range > 2.0)
    throw Error("jDE: F must stay in (0, 2]: f_lower > 0, f_range >= 0, f_lower + f_range <= 2");
}

SelfAdaptiveDe::SelfAdaptiveDe(const JdeParams& params) : params_(params) {
  ValidateJdeParams(params_);
}

void SelfAdaptiveDe::DoInitialize(const Problem& problem, Rng& rng) {
  Algorithm::DoInitialize(problem, rng);
  control_.resize(2, population_.x.cols());
  control_.row(0).setConstant(params_.f_initial);
  control_.row(1).setConstant(params_.cr_initial);
}

void SelfAdaptiveDe::DoStep(const Problem& problem, Rng& rng) {
  const Eigen::MatrixXd& x = population_.x;
  trials_.resize(x.rows(), x.cols());
  trial_control_ = control_;
  const std::size_t best = population_.BestIndex();
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    if (rng.Uniform() < params_.tau_f)
      trial_control_(0, i) = params_.f_lower + params_.f_range * rng.Uniform();
    if (rng.Uniform() < params_.tau_cr) trial_control_(1, i) = rng.Uniform();
    BuildDeTrial(problem, params_.strategy, x, static_cast<std::size_t>(i), best,
                 trial_control_(0, i), trial_control_(1, i), rng, mutant_, trials_.col(i));
  }
  Evaluate(problem, trials_, trial_f_);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    if (trial_f_(0, i) <= population_.f(0, i)) {
      population_.x.col(i) = trials_.col(i);
      population_.f.col(i) = trial_f_.col(i);
      control_.col(i) = trial_control_.col(i);
    }
  }
}

void SelfAdaptiveDe::Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::VectorXd>& f) {
  Algorithm::Replace(index, x, f);
  // An immigrant arrives without control parameters; it starts from the initial ones.
  control_(0, static_cast<Eigen::Index>(index)) = params_.f_initial;
  control_(1, static_cast<Eigen::Index>(index)) = params_.cr_initial;
}

void SelfAdaptiveDe::SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const {
  memory["control"] = control_;
}

void SelfAdaptiveDe::RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) {
  control_ = MemoryEntry(memory, "control", 2, population_.x.cols());
}

}  // namespace evoslam
