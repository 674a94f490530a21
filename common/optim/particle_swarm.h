#ifndef EVOSLAM_COMMON_OPTIM_PARTICLE_SWARM_H_
#define EVOSLAM_COMMON_OPTIM_PARTICLE_SWARM_H_

#include <cstddef>
#include <string_view>

#include "common/optim/algorithm.h"

namespace evoslam {

// Whom a particle follows: the best of the whole swarm, or the best of itself and its two
// neighbours on a ring of particle indices (slower to converge, harder to trap).
enum class PsoNeighbourhood { kGlobal, kRing };
PsoNeighbourhood ParsePsoNeighbourhood(std::string_view name);  // "global" | "ring"
std::string_view PsoNeighbourhoodName(PsoNeighbourhood neighbourhood);

// Inertia-weight PSO. Defaults are Clerc's constriction-equivalent settings; the velocity of each
// coordinate is clamped to vmax_fraction of the box width.
struct PsoParams {
  std::size_t particles = 25;
  double inertia = 0.7298;
  double c1 = 1.49618;  // pull towards the particle's own best
  double c2 = 1.49618;  // pull towards the neighbourhood's best
  double vmax_fraction = 0.5;
  PsoNeighbourhood neighbourhood = PsoNeighbourhood::kGlobal;
};

void ValidatePsoParams(const PsoParams& params);

// Each generation moves every particle, evaluates the swarm as one batch, then updates the
// personal bests. Particles that leave the box stop at its wall with zero velocity along that
// coordinate. The population other islands see is the personal bests; an immigrant becomes a
// particle's position and personal best, keeping its velocity.
class ParticleSwarm : public Algorithm {
 public:
  explicit ParticleSwarm(const PsoParams& params);
  std::string_view name() const override { return "pso"; }
  const PsoParams& params() const { return params_; }

  void Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
               const Eigen::Ref<const Eigen::VectorXd>& f) override;

 protected:
  void DoInitialize(const Problem& problem, Rng& rng) override;
  void DoStep(const Problem& problem, Rng& rng) override;
  std::size_t PopulationSize() const override { return params_.particles; }
  void SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const override;
  void RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) override;

 private:
  // The best personal best among the particle and its two ring neighbours, first on ties.
  std::size_t RingLeader(std::size_t particle) const;

  PsoParams params_;
  Eigen::MatrixXd position_;
  Eigen::MatrixXd velocity_;
  Eigen::MatrixXd position_f_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_PARTICLE_SWARM_H_
