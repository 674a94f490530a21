#ifndef EVOSLAM_COMMON_OPTIM_GA_PARAMS_H_
#define EVOSLAM_COMMON_OPTIM_GA_PARAMS_H_

#include <cstddef>
#include <string_view>

namespace evoslam {

// How two parents' bit strings are mixed: two cut points with the bits between them exchanged,
// or every bit exchanged independently with probability 1/2 (003 tried both; see
// docs/genetic_algorithms.md).
enum class GaCrossover { kTwoPoint, kUniform };
GaCrossover ParseGaCrossover(std::string_view name);  // "two-point" | "uniform"
std::string_view GaCrossoverName(GaCrossover crossover);

// The working parameters shared by the SGA and the aGA. Defaults follow 003's localization
// settings where the paper states them (16 bits a coordinate, two-point crossover, 5 pairs,
// 2 elitist mutants, the 8 worst replaced); the others are this project's choices, documented in
// docs/genetic_algorithms.md.
struct GaParams {
  std::size_t population = 20;
  // Bits of each coordinate's code, 1..30.
  int bits = 16;
  // Spacing of the search grid (the papers' 1 cm mesh); 0 spreads the codes over the whole box.
  double grid_step = 0.0;
  GaCrossover crossover = GaCrossover::kTwoPoint;
  // Share of the population, best first, that forms the mating pool.
  double elite_fraction = 0.5;
  // Parent pairs drawn from the pool each generation; each pair gives two children.
  std::size_t pairs = 5;
  // New individuals drawn near the best one each generation.
  std::size_t mutants = 2;
  // Half-width of the mutants' box around the best individual, as a share of each coordinate's
  // range.
  double mutation_box = 0.05;
  // How many of the worst individuals the best new candidates replace each generation.
  std::size_t replaced = 8;
  // Probability of flipping each bit of a crossover child. 003 has no such mutation (0); on
  // problems of many coordinates, where crossover alone soon runs out of new bits, about one flip
  // per child (1 / (bits * dimension)) helps.
  double bit_flip = 0.0;
};

// Throws Error naming the parameter that cannot work.
void ValidateGaParams(const GaParams& params);

// The number of individuals in the mating pool: elite_fraction of the population, rounded.
std::size_t MatingPoolSize(const GaParams& params);
// The number of candidates evaluated each generation: two children a pair, plus the mutants.
std::size_t CandidatesPerGeneration(const GaParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_GA_PARAMS_H_
