#include "common/util/random.h"

#include <cmath>
#include <numbers>

namespace evoslam {
namespace {

std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t MixBits(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

Rng::Rng(std::uint64_t seed) : seed_(seed) {
  std::uint64_t x = seed;
  for (auto& s : s_) {
    x = MixBits(x);
    s = x;
  }
}

RngState Rng::state() const { return RngState{seed_, {s_[0], s_[1], s_[2], s_[3]}}; }

Rng Rng::FromState(const RngState& state) {
  Rng rng(state.seed);
  for (std::size_t i = 0; i < 4; ++i) rng.s_[i] = state.words[i];
  return rng;
}

Rng Rng::Stream(std::uint64_t stream) const {
  return Rng(MixBits(seed_ ^ MixBits(stream + 0x632be59bd9b4e019ULL)));
}

std::uint64_t Rng::NextU64() {
  const std::uint64_t result = Rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = Rotl(s_[3], 45);
  return result;
}

double Rng::Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

double Rng::Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

std::size_t Rng::UniformIndex(std::size_t n) {
  // Rejection of the short top interval keeps every index equally likely.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t x;
  do {
    x = NextU64();
  } while (x >= limit);
  return static_cast<std::size_t>(x % n);
}

double Rng::Normal() {
  double u1;
  do {
    u1 = Uniform();
  } while (u1 <= 0.0);
  const double u2 = Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double Rng::Normal(double mean, double sigma) { return mean + sigma * Normal(); }

}  // namespace evoslam
