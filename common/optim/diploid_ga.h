#ifndef EVOSLAM_COMMON_OPTIM_DIPLOID_GA_H_
#define EVOSLAM_COMMON_OPTIM_DIPLOID_GA_H_

#include <map>
#include <string>
#include <string_view>

#include "common/optim/binary_ga.h"

namespace evoslam {

// The aGA that 003 compares with its SGA (Moravec 2012): the same parameters and operators, but
// every individual carries two chromosomes. Only the expressed one is decoded and evaluated, so a
// generation costs what the SGA's does; the dormant one is a reservoir of bits that selection does
// not see. The papers leave the mechanism open; this is the project's reading:
//  - the pair (a, b) gives two children. The first is the crossover of a's expressed chromosome
//    with b's dormant one: it expresses a's string with the exchanged bits taken from b's dormant
//    string and keeps the complementary string dormant, so breeding loses no bits. The second
//    does the same with a and b swapped;
//  - a mutant is a copy of a random individual whose expressed chromosome is redrawn near the
//    best; it keeps that individual's dormant chromosome;
//  - an immigrant replaces the expressed chromosome only.
// The dormant chromosomes thus change only by the segments crossover exchanges, and keep the
// population from collapsing onto one point (docs/genetic_algorithms.md has the measurements).
class AdaptiveGa : public BinaryGa {
 public:
  explicit AdaptiveGa(const GaParams& params) : BinaryGa(params) {}
  std::string_view name() const override { return "aga"; }

  // Each individual's dormant chromosome, one column per individual.
  const Chromosomes& dormant() const { return dormant_; }

 protected:
  // Random expressed and dormant chromosomes.
  void DoInitialize(const Problem& problem, Rng& rng) override;
  void SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const override;
  void RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) override;
  void Breed(const std::vector<std::size_t>& ranking, Rng& rng, Chromosomes& offspring) override;
  void Settle(std::size_t index, std::size_t candidate) override;

 private:
  Chromosomes dormant_;
  // The dormant chromosomes of the candidates Breed made, column for column.
  Chromosomes offspring_dormant_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_DIPLOID_GA_H_
