#ifndef EVOSLAM_COMMON_UTIL_RANDOM_H_
#define EVOSLAM_COMMON_UTIL_RANDOM_H_

#include <array>
#include <cstddef>
#include <cstdint>

namespace evoslam {

// Everything that determines a generator's future output; what a checkpoint stores.
struct RngState {
  std::uint64_t seed = 0;
  std::array<std::uint64_t, 4> words{};
};

// A small, fast generator (xoshiro256**) with hand-written distributions, so that a seed gives the
// same numbers with every compiler and standard library (std:: distributions are not portable).
class Rng {
 public:
  explicit Rng(std::uint64_t seed);

  // An independent generator for sub-task `stream` (a scan, an island, a migration), derived from
  // this generator's seed; it does not advance this generator.
  Rng Stream(std::uint64_t stream) const;

  std::uint64_t NextU64();
  double Uniform();                         // [0, 1)
  double Uniform(double lo, double hi);     // [lo, hi)
  std::size_t UniformIndex(std::size_t n);  // [0, n), unbiased; n > 0
  double Normal();                          // standard normal (Box-Muller)
  double Normal(double mean, double sigma);

  std::uint64_t seed() const { return seed_; }
  RngState state() const;
  // Continues exactly where the generator that gave `state` stood.
  static Rng FromState(const RngState& state);

 private:
  std::uint64_t seed_;
  std::uint64_t s_[4];
};

// Mixes a 64-bit value (SplitMix64 finaliser); used to derive seeds.
std::uint64_t MixBits(std::uint64_t x);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_RANDOM_H_
