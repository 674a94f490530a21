#ifndef EVOSLAM_COMMON_OPTIM_IMMUNITY_H_
#define EVOSLAM_COMMON_OPTIM_IMMUNITY_H_

#include <Eigen/Core>

#include "common/util/random.h"

namespace evoslam {

// The problem-specific half of the immune MOEA (Li 2006, sections 3.3-3.4). Vaccination is a
// local repair that uses knowledge the generic operators lack (in SLAM: a key point grid the
// robot should see); immune selection judges the repair on a cheap local measure before the
// candidate costs a full evaluation. Both are called from one thread at a time but on several
// islands at once, so implementations must be thread-safe.
class Immunity {
 public:
  virtual ~Immunity() = default;

  // Changes x in place; returns false when the vaccine does not apply to this candidate.
  virtual bool Vaccinate(Eigen::Ref<Eigen::VectorXd> x, Rng& rng) const = 0;

  // Whether the vaccinated candidate replaces the original.
  virtual bool Accept(const Eigen::Ref<const Eigen::VectorXd>& original,
                      const Eigen::Ref<const Eigen::VectorXd>& vaccinated, Rng& rng) const = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_IMMUNITY_H_
