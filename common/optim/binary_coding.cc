#include "common/optim/binary_coding.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/util/error.h"

namespace evoslam {
namespace {

// Grid indices beyond this would lose integer precision in a double.
constexpr double kMaxGridPoints = 9007199254740992.0;  // 2^53

}  // namespace

BinaryCoding::BinaryCoding(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int bits,
                           double grid_step)
    : bits_(bits) {
  if (bits < 1 || bits > 30) throw Error("binary coding: bits must be in 1..30");
  if (!(grid_step >= 0.0)) throw Error("binary coding: grid step must be >= 0");
  max_code_ = (std::uint32_t{1} << bits) - 1;
  axes_.resize(static_cast<std::size_t>(lower.size()));
  for (Eigen::Index j = 0; j < lower.size(); ++j) {
    Axis& axis = axes_[static_cast<std::size_t>(j)];
    axis.lower = lower(j);
    axis.upper = upper(j);
    axis.step = grid_step;
    if (grid_step > 0.0) {
      // The small slack keeps the upper bound when rounding leaves width/step just below an
      // integer, as the exhaustive search does.
      const double last = std::floor((upper(j) - lower(j)) / grid_step + 1e-9);
      if (!(last < kMaxGridPoints))
        throw Error("binary coding: grid step is too fine for the box of coordinate " +
                    std::to_string(j));
      axis.last = static_cast<std::uint64_t>(last);
    }
  }
}

std::uint64_t BinaryCoding::Level(const Axis& axis, std::uint32_t code) const {
  const std::uint64_t codes = std::uint64_t{max_code_} + 1;
  const std::uint64_t points = axis.last + 1;
  // Both products stay below 2^60: points <= codes <= 2^30 here.
  if (points <= codes) return std::uint64_t{code} * points / codes;
  return static_cast<std::uint64_t>(
      std::llround(static_cast<double>(code) * static_cast<double>(axis.last) / max_code_));
}

double BinaryCoding::Decode(Eigen::Index coordinate, std::uint32_t code) const {
  const Axis& axis = axes_[static_cast<std::size_t>(coordinate)];
  const double value =
      axis.step > 0.0
          ? axis.lower + static_cast<double>(Level(axis, code)) * axis.step
          : axis.lower + (axis.upper - axis.lower) * (static_cast<double>(code) / max_code_);
  // Rounding may put the last point an ulp (or the grid's slack) past the upper bound.
  return std::min(value, axis.upper);
}

std::uint32_t BinaryCoding::Encode(Eigen::Index coordinate, double value) const {
  const Axis& axis = axes_[static_cast<std::size_t>(coordinate)];
  const double width = axis.upper - axis.lower;
  const double v = std::clamp(value, axis.lower, axis.upper);
  if (axis.step == 0.0) {
    if (width == 0.0) return 0;
    return static_cast<std::uint32_t>(std::clamp(std::llround((v - axis.lower) / width * max_code_),
                                                 0LL, static_cast<long long>(max_code_)));
  }
  const double nearest =
      std::min(std::round((v - axis.lower) / axis.step), static_cast<double>(axis.last));
  const std::uint64_t codes = std::uint64_t{max_code_} + 1;
  const std::uint64_t points = axis.last + 1;
  if (points <= codes) {
    // The first code of the point's run.
    const auto k = static_cast<std::uint64_t>(nearest);
    return static_cast<std::uint32_t>((k * codes + axis.last) / points);
  }
  // Fewer codes than points: the nearest of the codes around the proportional guess.
  const long long guess = std::llround(nearest * max_code_ / static_cast<double>(axis.last));
  std::uint32_t best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (long long c = std::max(guess - 1, 0LL);
       c <= std::min(guess + 1, static_cast<long long>(max_code_)); ++c) {
    const double distance = std::abs(Decode(coordinate, static_cast<std::uint32_t>(c)) - v);
    if (distance < best_distance) {
      best_distance = distance;
      best = static_cast<std::uint32_t>(c);
    }
  }
  return best;
}

void BinaryCoding::Decode(const Eigen::Ref<const Chromosome>& chromosome,
                          Eigen::Ref<Eigen::VectorXd> x) const {
  for (Eigen::Index j = 0; j < chromosome.size(); ++j) x(j) = Decode(j, chromosome(j));
}

Chromosome BinaryCoding::Encode(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Chromosome chromosome(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) chromosome(j) = Encode(j, x(j));
  return chromosome;
}

Chromosome BinaryCoding::Random(Rng& rng) const {
  Chromosome chromosome(dimension());
  for (Eigen::Index j = 0; j < chromosome.size(); ++j)
    chromosome(j) = static_cast<std::uint32_t>(rng.NextU64() >> (64 - bits_));
  return chromosome;
}

Eigen::MatrixXd BinaryCoding::Box() const {
  Eigen::MatrixXd box(dimension(), 2);
  for (Eigen::Index j = 0; j < box.rows(); ++j) {
    box(j, 0) = axes_[static_cast<std::size_t>(j)].lower;
    box(j, 1) = axes_[static_cast<std::size_t>(j)].upper;
  }
  return box;
}

void DecodeCandidates(const Problem& problem, const BinaryCoding& coding,
                      const Chromosomes& chromosomes, Eigen::MatrixXd& x) {
  x.resize(chromosomes.rows(), chromosomes.cols());
  for (Eigen::Index i = 0; i < chromosomes.cols(); ++i) {
    coding.Decode(chromosomes.col(i), x.col(i));
    if (problem.encoding() != Encoding::kReal) Conform(problem, x.col(i));
  }
}

Eigen::MatrixXd ChromosomesToMemory(const Chromosomes& chromosomes) {
  return chromosomes.cast<double>();
}

Chromosomes ChromosomesFromMemory(const Eigen::MatrixXd& memory, int bits,
                                  const std::string& name) {
  const double codes = static_cast<double>(std::uint64_t{1} << bits);
  for (Eigen::Index i = 0; i < memory.size(); ++i) {
    const double v = memory.data()[i];
    if (!(v >= 0.0 && v < codes && v == std::floor(v)))
      throw Error("checkpoint memory '" + name + "' holds " + std::to_string(v) +
                  ", not a code of " + std::to_string(bits) + " bits");
  }
  return memory.cast<std::uint32_t>();
}

}  // namespace evoslam
