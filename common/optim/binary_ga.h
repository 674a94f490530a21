#ifndef EVOSLAM_COMMON_OPTIM_BINARY_GA_H_
#define EVOSLAM_COMMON_OPTIM_BINARY_GA_H_

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "common/optim/algorithm.h"
#include "common/optim/binary_coding.h"
#include "common/optim/ga_params.h"

namespace evoslam {

// The generation the SGA and the aGA share (003): rank the population, breed the new candidates
// (2 x pairs children of parents from the mating pool, then the elitist mutants), evaluate them as
// one batch, and put the best of them in place of the `replaced` worst individuals. The best
// individual always survives. Subclasses decide how a candidate's chromosome is bred.
//
// The population other islands see is the decoded chromosomes; an immigrant's chromosome is the
// code nearest its position (it keeps its exact position and fitness until replaced).
class BinaryGa : public Algorithm {
 public:
  const GaParams& params() const { return params_; }
  // The chromosome each individual expresses, one column per individual.
  const Chromosomes& chromosomes() const { return chromosomes_; }

  void Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
               const Eigen::Ref<const Eigen::VectorXd>& f) override;

 protected:
  // Throws Error when the parameters cannot work (ValidateGaParams).
  explicit BinaryGa(const GaParams& params);

  // Random chromosomes, decoded and evaluated.
  void DoInitialize(const Problem& problem, Rng& rng) override;
  void DoStep(const Problem& problem, Rng& rng) override;
  std::size_t PopulationSize() const override { return params_.population; }
  void SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const override;
  void RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) override;

  // Fills every column of `offspring`: first the children, pair after pair, then the mutants.
  // `ranking` lists the population best first.
  virtual void Breed(const std::vector<std::size_t>& ranking, Rng& rng, Chromosomes& offspring) = 0;
  // Candidate `candidate` is about to take the place of individual `index`.
  virtual void Settle(std::size_t /*index*/, std::size_t /*candidate*/) {}

  const BinaryCoding& coding() const { return coding_; }

 private:
  GaParams params_;
  BinaryCoding coding_;  // built by DoInitialize or RestoreMemory
  Chromosomes chromosomes_;
  Chromosomes offspring_;
  Eigen::MatrixXd candidates_;
  Eigen::MatrixXd candidate_f_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_BINARY_GA_H_
