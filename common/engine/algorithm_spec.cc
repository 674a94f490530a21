#include "common/engine/algorithm_spec.h"

#include <array>
#include <utility>

#include "common/optim/diploid_ga.h"
#include "common/optim/simple_ga.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::array<std::pair<AlgorithmKind, std::string_view>, 7> kNames = {{
    {AlgorithmKind::kDe, "de"},
    {AlgorithmKind::kJde, "jde"},
    {AlgorithmKind::kPso, "pso"},
    {AlgorithmKind::kSga, "sga"},
    {AlgorithmKind::kAga, "aga"},
    {AlgorithmKind::kMuPlusLambda, "mu+lambda"},
    {AlgorithmKind::kImmune, "immune"},
}};

}  // namespace

AlgorithmKind ParseAlgorithmKind(std::string_view name) {
  for (const auto& [kind, n] : kNames) {
    if (n == name) return kind;
  }
  std::string valid;
  for (const auto& [kind, n] : kNames) valid += (valid.empty() ? "" : ", ") + std::string(n);
  throw Error("unknown algorithm '" + std::string(name) + "' (expected one of: " + valid + ")");
}

std::string_view AlgorithmKindName(AlgorithmKind kind) {
  for (const auto& [k, n] : kNames) {
    if (k == kind) return n;
  }
  return "unknown";
}

std::vector<std::string> AlgorithmKindNames() {
  std::vector<std::string> names;
  for (const auto& [kind, n] : kNames) names.emplace_back(n);
  return names;
}

std::unique_ptr<Algorithm> MakeAlgorithm(const AlgorithmSpec& spec) {
  switch (spec.kind) {
    case AlgorithmKind::kDe:
      return std::make_unique<DifferentialEvolution>(spec.de);
    case AlgorithmKind::kJde:
      return std::make_unique<SelfAdaptiveDe>(spec.jde);
    case AlgorithmKind::kPso:
      return std::make_unique<ParticleSwarm>(spec.pso);
    case AlgorithmKind::kSga:
      return std::make_unique<SimpleGa>(spec.ga);
    case AlgorithmKind::kAga:
      return std::make_unique<AdaptiveGa>(spec.ga);
    case AlgorithmKind::kMuPlusLambda:
      return std::make_unique<MuPlusLambdaEa>(spec.mu_plus_lambda);
    case AlgorithmKind::kImmune:
      return std::make_unique<ImmuneMoea>(spec.immune);
  }
  throw Error("unknown algorithm kind");
}

std::size_t PopulationSize(const AlgorithmSpec& spec) {
  switch (spec.kind) {
    case AlgorithmKind::kDe:
      return spec.de.population;
    case AlgorithmKind::kJde:
      return spec.jde.population;
    case AlgorithmKind::kPso:
      return spec.pso.particles;
    case AlgorithmKind::kSga:
    case AlgorithmKind::kAga:
      return spec.ga.population;
    case AlgorithmKind::kMuPlusLambda:
      return spec.mu_plus_lambda.mu;
    case AlgorithmKind::kImmune:
      return spec.immune.population;
  }
  return 0;
}

}  // namespace evoslam
