#include "common/engine/algorithm_spec.h"

#include <array>
#include <utility>

#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::array<std::pair<AlgorithmKind, std::string_view>, 3> kNames = {{
    {AlgorithmKind::kDe, "de"},
    {AlgorithmKind::kJde, "jde"},
    {AlgorithmKind::kPso, "pso"},
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
  }
  return 0;
}

}  // namespace evoslam
