#include "common/optim/binary_ga.h"

#include "common/optim/ga_operators.h"

namespace evoslam {

BinaryGa::BinaryGa(const GaParams& params) : params_(params) { ValidateGaParams(params_); }

void BinaryGa::DoInitialize(const Problem& problem, Rng& rng) {
  coding_ = BinaryCoding(problem.lower(), problem.upper(), params_.bits, params_.grid_step);
  chromosomes_.resize(coding_.dimension(), static_cast<Eigen::Index>(params_.population));
  for (Eigen::Index i = 0; i < chromosomes_.cols(); ++i) chromosomes_.col(i) = coding_.Random(rng);
  DecodeCandidates(problem, coding_, chromosomes_, population_.x);
  Evaluate(problem, population_.x, population_.f);
}

void BinaryGa::DoStep(const Problem& problem, Rng& rng) {
  const std::vector<std::size_t> ranking = RankByFitness(population_.f);
  offspring_.resize(chromosomes_.rows(),
                    static_cast<Eigen::Index>(CandidatesPerGeneration(params_)));
  Breed(ranking, rng, offspring_);
  for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(2 * params_.pairs); ++c)
    FlipBits(params_.bits, params_.bit_flip, rng, offspring_.col(c));
  DecodeCandidates(problem, coding_, offspring_, candidates_);
  Evaluate(problem, candidates_, candidate_f_);
  for (const auto& [index, candidate] : ReplaceWorst(ranking, candidate_f_, params_.replaced)) {
    Settle(index, candidate);
    const auto i = static_cast<Eigen::Index>(index);
    const auto c = static_cast<Eigen::Index>(candidate);
    chromosomes_.col(i) = offspring_.col(c);
    population_.x.col(i) = candidates_.col(c);
    population_.f.col(i) = candidate_f_.col(c);
  }
}

void BinaryGa::Replace(std::size_t index, const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const Eigen::VectorXd>& f) {
  Algorithm::Replace(index, x, f);
  chromosomes_.col(static_cast<Eigen::Index>(index)) = coding_.Encode(x);
}

void BinaryGa::SaveMemory(std::map<std::string, Eigen::MatrixXd>& memory) const {
  memory["chromosomes"] = ChromosomesToMemory(chromosomes_);
  memory["box"] = coding_.Box();
}

void BinaryGa::RestoreMemory(const std::map<std::string, Eigen::MatrixXd>& memory) {
  const Eigen::Index dim = population_.x.rows();
  const Eigen::Index n = population_.x.cols();
  const Eigen::MatrixXd& box = MemoryEntry(memory, "box", dim, 2);
  coding_ = BinaryCoding(box.col(0), box.col(1), params_.bits, params_.grid_step);
  chromosomes_ = ChromosomesFromMemory(MemoryEntry(memory, "chromosomes", dim, n), params_.bits,
                                       "chromosomes");
}

}  // namespace evoslam
