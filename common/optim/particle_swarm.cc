#include "common/optim/particle_swarm.h"

#include <algorithm>
#include <string>

#include "common/util/error.h"

namespace evoslam {

PsoNeighbourhood ParsePsoNeighbourhood(std::string_view name) {
  if (name == "global") return PsoNeighbourhood::kGlobal;
  if (name == "ring") return PsoNeighbourhood::kRing;
  throw Error("unknown PSO neighbourhood '" + std::string(name) + "' (expected global or ring)");
}

std::string_view PsoNeighbourhoodName(PsoNeighbourhood neighbourhood) {
  return neighbourhood == PsoNeighbourhood::kGlobal ? "global" : "ring";
}

void ValidatePsoParams(const PsoParams& params) {
  if (params.particles < 2) throw Error("particle swarm: needs at least 2 particles");
  if (!(params.vmax_fraction > 0.0))
    throw Error("particle swarm: velocity clamp must be positive, or particles never move");
  if (!(params.inertia >= 0.0) || !(params.c1 >= 0.0) || !(params.c2 >= 0.0))
    throw Error("particle swarm: inertia, c1 and c2 must be >= 0");
}

ParticleSwarm::ParticleSwarm(const PsoParams& params) : params_(params) {
  ValidatePsoParams(params_);
}

void ParticleSwarm::DoInitialize(const Problem& problem, Rng& rng) {
  Algorithm::DoInitialize(problem, rng);
  const Eigen::VectorXd vmax = params_.vmax_fraction * (problem.upper() - problem.lower());
  position_ = population_.x;
  position_f_ = population_.f;
  velocity_.resize(position_.rows(), position_.cols());
  for (Eigen::Index i = 0; i < velocity_.cols(); ++i) {
    for (Eigen::Index j = 0; j < velocity_.rows(); ++j)
      velocity_(j, i) = rng.Uniform(-vmax(j), vmax(j));
  }
}

std::size_t ParticleSwarm::RingLeader(std::size_t particle) const {
  const std::size_t n = population_.size();
  const std::size_t candidates[3] = {(particle + n - 1) % n, particle, (particle + 1) % n};
  std::size_t leader = candidates[0];
  for (const std::size_t c : candidates) {
    if (population_.f(0, static_cast<Eigen::Index>(c)) <
        population_.f(0, static_cast<Eigen::Index>(leader)))
      leader = c;
  }
  return leader;
}

void ParticleSwarm::DoStep(const Problem& problem, Rng& rng) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  const Eigen::VectorXd vmax = params_.vmax_fraction * (hi - lo);
  const Eigen::MatrixXd& personal = population_.x;
  const std::size_t global = population_.BestIndex();
  for (Eigen::Index i = 0; i < position_.cols(); ++i) {
    const auto leader = static_cast<Eigen::Index>(params_.neighbourhood == PsoNeighbourhood::kGlobal
                                                      ? global
                                                      : RingLeader(static_cast<std::size_t>(i)));
    for (Eigen::Index j = 0; j < position_.rows(); ++j) {
      const double r1 = rng.Uniform();
      const double r2 = rng.Uniform();
      double v = params_.inertia * velocity_(j, i) +
                 params_.c1 * r1 * (personal(j, i) - position_(j, i)) +
                 params_.c2 * r2 * (personal(j, leader) - position_(j, i));
      v = std::clamp(v, -vmax(j), vmax(j));
      double x = position_(j, i) + v;
      if (x < lo(j) || x > hi(j)) {
        x = std::clamp(x, lo(j), hi(j));
        v = 0.0;
      }
      velocity_(j, i) = v;
      position_(j, i) = x;
    }
    if (problem.encoding() != Encoding::kReal) Conform(problem, position_.col(i));
  }
  Evaluate(problem, position_, position_f_);
  for (Eigen::Index i = 0; i < position_.cols(); ++i) {
    if (position_f_(0, i) < population_.f(0, i)) {
      population_.x.col(i) = position_.col(i);
      population_.f.col(i) = position_f_.col(i);
    }
  }
}

void ParticleSwarm::Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
                            const Eigen::Ref<const Eigen::VectorXd>& f) {
  Algorithm::Replace(index, x, f);
  position_.col(static_cast<Eigen::Index>(index)) = x;
  position_f_.col(static_cast<Eigen::Index>(index)) = f;
}

void ParticleSwarm::SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const {
  memory["position"] = position_;
  memory["position_f"] = position_f_;
  memory["velocity"] = velocity_;
}

void ParticleSwarm::RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) {
  const Eigen::Index dim = population_.x.rows();
  const Eigen::Index n = population_.x.cols();
  position_ = MemoryEntry(memory, "position", dim, n);
  position_f_ = MemoryEntry(memory, "position_f", population_.f.rows(), n);
  velocity_ = MemoryEntry(memory, "velocity", dim, n);
}

}  // namespace evoslam
