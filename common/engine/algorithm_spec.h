#ifndef EVOSLAM_COMMON_ENGINE_ALGORITHM_SPEC_H_
#define EVOSLAM_COMMON_ENGINE_ALGORITHM_SPEC_H_

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/optim/algorithm.h"
#include "common/optim/differential_evolution.h"
#include "common/optim/ga_params.h"
#include "common/optim/immune_moea.h"
#include "common/optim/mu_plus_lambda.h"
#include "common/optim/particle_swarm.h"
#include "common/optim/self_adaptive_de.h"

namespace evoslam {

enum class AlgorithmKind { kDe, kJde, kPso, kSga, kAga, kMuPlusLambda, kImmune };

// Names as on the command line and in checkpoints: "de", "jde", "pso", ...
AlgorithmKind ParseAlgorithmKind(std::string_view name);  // throws Error listing the valid names
std::string_view AlgorithmKindName(AlgorithmKind kind);
std::vector<std::string> AlgorithmKindNames();

// Which algorithm, with which parameters: everything needed to build an instance. Only the
// parameters of `kind` are used; the others keep their defaults so that switching kind on the
// command line needs no other change.
struct AlgorithmSpec {
  AlgorithmKind kind = AlgorithmKind::kDe;
  DeParams de;
  JdeParams jde;
  PsoParams pso;
  GaParams ga;  // sga and aga
  MuPlusLambdaParams mu_plus_lambda;
  ImmuneMoeaParams immune;
};

// Builds the algorithm; throws Error when its parameters cannot work.
std::unique_ptr<Algorithm> MakeAlgorithm(const AlgorithmSpec& spec);

// The number of individuals the spec's algorithm keeps.
std::size_t PopulationSize(const AlgorithmSpec& spec);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_ENGINE_ALGORITHM_SPEC_H_
