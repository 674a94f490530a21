#ifndef EVOSLAM_COMMON_OPTIM_GA_OPERATORS_H_
#define EVOSLAM_COMMON_OPTIM_GA_OPERATORS_H_

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "common/optim/binary_coding.h"
#include "common/optim/ga_params.h"
#include "common/optim/population.h"
#include "common/util/random.h"

namespace evoslam {

// Crosses two chromosomes read as one bit string (coordinate 0 first, each code's most significant
// bit first) and writes the two complementary children: `child_a` is `a` with the exchanged bits
// taken from `b`, `child_b` the reverse. Two-point: two distinct cut points among the string's
// bit boundaries, the bits between them exchanged. Uniform: each bit exchanged with probability
// 1/2.
void CrossChromosomes(GaCrossover kind, int bits, const Eigen::Ref<const Chromosome>& a,
                      const Eigen::Ref<const Chromosome>& b, Rng& rng,
                      Eigen::Ref<Chromosome> child_a, Eigen::Ref<Chromosome> child_b);

// Elitist mutation: every code drawn anew, uniformly among the codes within box_fraction of the
// code range of `best`'s (cut at the first and last code), so the mutant lands near the best
// individual.
void MutateNearBest(const Eigen::Ref<const Chromosome>& best, std::uint32_t max_code,
                    double box_fraction, Rng& rng, Eigen::Ref<Chromosome> mutant);

// Flips each of the `bits` low bits of every code with the given probability.
void FlipBits(int bits, double probability, Rng& rng, Eigen::Ref<Chromosome> chromosome);

// Two distinct members of the mating pool, the first `pool` (>= 2) entries of `ranking`.
std::pair<std::size_t, std::size_t> DrawMates(const std::vector<std::size_t>& ranking,
                                              std::size_t pool, Rng& rng);

// Who replaces whom: (population index, candidate index) pairs that give the `count` worst of
// `ranking` the `count` best candidates, the worst individual the best candidate.
std::vector<std::pair<std::size_t, std::size_t>> ReplaceWorst(
    const std::vector<std::size_t>& ranking, const Eigen::MatrixXd& candidate_f, std::size_t count);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_GA_OPERATORS_H_
