#include "common/optim/ga_operators.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace evoslam {
namespace {

// The bits of one code that lie in [first, last) of the whole string, as a mask of that code.
std::uint32_t SegmentMask(std::size_t code_index, int bits, std::size_t first, std::size_t last) {
  const std::size_t begin = code_index * static_cast<std::size_t>(bits);
  const std::size_t end = begin + static_cast<std::size_t>(bits);
  const std::size_t from = std::max(first, begin);
  const std::size_t to = std::min(last, end);
  if (from >= to) return 0;
  // String position begin + k is bit (bits - 1 - k) of the code.
  const auto high = static_cast<unsigned>(end - from);  // bits at or below position `from`
  const auto low = static_cast<unsigned>(end - to);
  return static_cast<std::uint32_t>((std::uint64_t{1} << high) - (std::uint64_t{1} << low));
}

}  // namespace

void CrossChromosomes(GaCrossover kind, int bits, const Eigen::Ref<const Chromosome>& a,
                      const Eigen::Ref<const Chromosome>& b, Rng& rng,
                      Eigen::Ref<Chromosome> child_a, Eigen::Ref<Chromosome> child_b) {
  const Eigen::Index dim = a.size();
  const std::uint32_t all = static_cast<std::uint32_t>((std::uint64_t{1} << bits) - 1);
  std::size_t first = 0;
  std::size_t last = 0;
  if (kind == GaCrossover::kTwoPoint) {
    const std::size_t length = static_cast<std::size_t>(dim) * static_cast<std::size_t>(bits);
    // A one-bit string has a single boundary: nothing to exchange.
    if (length >= 2) {
      first = rng.UniformIndex(length);
      last = rng.UniformIndex(length - 1);
      if (last >= first) ++last;
      if (first > last) std::swap(first, last);
    }
  }
  for (Eigen::Index j = 0; j < dim; ++j) {
    const std::uint32_t mask = kind == GaCrossover::kTwoPoint
                                   ? SegmentMask(static_cast<std::size_t>(j), bits, first, last)
                                   : static_cast<std::uint32_t>(rng.NextU64() >> (64 - bits)) & all;
    const std::uint32_t from_a = a(j);
    const std::uint32_t from_b = b(j);
    child_a(j) = (from_a & ~mask) | (from_b & mask);
    child_b(j) = (from_b & ~mask) | (from_a & mask);
  }
}

void MutateNearBest(const Eigen::Ref<const Chromosome>& best, std::uint32_t max_code,
                    double box_fraction, Rng& rng, Eigen::Ref<Chromosome> mutant) {
  const auto half = static_cast<std::int64_t>(std::llround(box_fraction * max_code));
  for (Eigen::Index j = 0; j < best.size(); ++j) {
    const auto centre = static_cast<std::int64_t>(best(j));
    const std::int64_t low = std::max<std::int64_t>(centre - half, 0);
    const std::int64_t high = std::min<std::int64_t>(centre + half, max_code);
    mutant(j) = static_cast<std::uint32_t>(low + static_cast<std::int64_t>(rng.UniformIndex(
                                                     static_cast<std::size_t>(high - low + 1))));
  }
}

std::pair<std::size_t, std::size_t> DrawMates(const std::vector<std::size_t>& ranking,
                                              std::size_t pool, Rng& rng) {
  const std::size_t first = rng.UniformIndex(pool);
  std::size_t second = rng.UniformIndex(pool - 1);
  if (second >= first) ++second;
  return {ranking[first], ranking[second]};
}

std::vector<std::pair<std::size_t, std::size_t>> ReplaceWorst(
    const std::vector<std::size_t>& ranking, const Eigen::MatrixXd& candidate_f,
    std::size_t count) {
  const std::vector<std::size_t> best_candidates = RankByFitness(candidate_f);
  std::vector<std::pair<std::size_t, std::size_t>> moves;
  moves.reserve(count);
  for (std::size_t k = 0; k < count; ++k)
    moves.emplace_back(ranking[ranking.size() - 1 - k], best_candidates[k]);
  return moves;
}

void FlipBits(int bits, double probability, Rng& rng, Eigen::Ref<Chromosome> chromosome) {
  if (probability <= 0.0) return;
  // Jump from one flipped bit to the next with geometrically distributed gaps: one draw per
  // flip instead of one per bit.
  const auto total = static_cast<double>(chromosome.size()) * bits;
  const double log_keep = std::log1p(-std::min(probability, 1.0 - 1e-12));
  double position = -1.0;
  for (;;) {
    position += 1.0 + std::floor(std::log1p(-rng.Uniform()) / log_keep);
    if (!(position < total)) return;
    const auto k = static_cast<std::int64_t>(position);
    chromosome(static_cast<Eigen::Index>(k / bits)) ^= std::uint32_t{1} << (k % bits);
  }
}

}  // namespace evoslam
