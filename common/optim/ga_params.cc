#include "common/optim/ga_params.h"

#include <cmath>
#include <string>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {

GaCrossover ParseGaCrossover(std::string_view name) {
  if (name == "two-point") return GaCrossover::kTwoPoint;
  if (name == "uniform") return GaCrossover::kUniform;
  throw Error("unknown GA crossover '" + std::string(name) + "' (expected two-point or uniform)");
}

std::string_view GaCrossoverName(GaCrossover crossover) {
  return crossover == GaCrossover::kTwoPoint ? "two-point" : "uniform";
}

std::size_t MatingPoolSize(const GaParams& params) {
  return static_cast<std::size_t>(
      std::lround(params.elite_fraction * static_cast<double>(params.population)));
}

std::size_t CandidatesPerGeneration(const GaParams& params) {
  return 2 * params.pairs + params.mutants;
}

void ValidateGaParams(const GaParams& params) {
  if (params.bits < 1 || params.bits > 30)
    throw Error("genetic algorithm: bits must be in 1..30, got " + std::to_string(params.bits));
  if (!IsFiniteNonNegative(params.grid_step))
    throw Error("genetic algorithm: grid step must be finite and >= 0");
  if (!(params.elite_fraction > 0.0 && params.elite_fraction <= 1.0))
    throw Error("genetic algorithm: elite fraction must be in (0, 1]");
  if (!(params.bit_flip >= 0.0 && params.bit_flip <= 1.0))
    throw Error("genetic algorithm: bit flip is a probability, in [0, 1]");
  if (!(params.mutation_box > 0.0 && params.mutation_box <= 1.0))
    throw Error("genetic algorithm: mutation box must be in (0, 1]");
  if (MatingPoolSize(params) < 2) {
    throw Error("genetic algorithm: the mating pool holds " +
                std::to_string(MatingPoolSize(params)) +
                " individuals, a pair needs 2 (raise the population or the elite fraction)");
  }
  if (params.replaced == 0)
    throw Error("genetic algorithm: replaced must be >= 1, or the population never changes");
  if (params.replaced >= params.population) {
    throw Error("genetic algorithm: replaced (" + std::to_string(params.replaced) +
                ") must be smaller than the population (" + std::to_string(params.population) +
                "), so that the best individual survives");
  }
  if (params.replaced > CandidatesPerGeneration(params)) {
    throw Error("genetic algorithm: replaced (" + std::to_string(params.replaced) +
                ") exceeds the new candidates of a generation (" +
                std::to_string(CandidatesPerGeneration(params)) + " = 2 x pairs + mutants)");
  }
}

}  // namespace evoslam
