#include "common/slam/immune/evidence_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// Past this many cells a beam's table of empty weights would be the size of a map.
constexpr double kMaxCellsPerBeam = 1e5;

// exp(-n kEvidenceUnit) for n below 2^17 (32 nats), as high[n >> 10] * low[n & 1023]: two tables
// that stay in the first-level cache. Beyond, 0: e^-32 is 1e-14, below what f1's unit resolves.
struct DecayTable {
  static constexpr int kLowBits = 10;
  static constexpr std::uint32_t kEnd = 1u << 17;
  std::array<double, (kEnd >> kLowBits)> high;
  std::array<double, (1u << kLowBits)> low;

  DecayTable() {
    for (std::size_t i = 0; i < high.size(); ++i) {
      high[i] = std::exp(-static_cast<double>(i << kLowBits) * kEvidenceUnit);
    }
    for (std::size_t i = 0; i < low.size(); ++i) {
      low[i] = std::exp(-static_cast<double>(i) * kEvidenceUnit);
    }
  }

  double operator()(std::uint32_t units) const {
    if (units >= kEnd) return 0.0;
    return high[units >> kLowBits] * low[units & ((1u << kLowBits) - 1)];
  }
};

const DecayTable kEvidenceDecay;

// The beliefs of a cell in a form safe at every limit. With hi >= lo the two sums, u = e^-hi,
// v = e^-lo and p = e^-(hi - lo) = u / v, dividing Dempster's rule through by v gives
//   belief(hi side) = (1 - u) / (1 + p - u),   belief(lo side) = (1 - v) p / (1 + p - u),
// whose denominator lies in [1, 2] unless hi = lo = 0: no overflow, no 0 / 0 as both sums grow.
struct DempsterTerms {
  double hi_belief;
  double lo_belief;  // min(occ, emp): the cell's contradiction
};

DempsterTerms Combine(std::uint32_t hi, std::uint32_t lo) {
  const double p = kEvidenceDecay(hi - lo);
  const double u = kEvidenceDecay(hi);
  const double v = kEvidenceDecay(lo);
  const double inverse = 1.0 / (1.0 + p - u);
  return {(1.0 - u) * inverse, (1.0 - v) * p * inverse};
}

}  // namespace

void ValidateEvidenceGridParams(const proto::EvidenceGridParams& p) {
  if (!IsFinitePositive(p.cell_size_m()))
    throw Error("evidence.cell_size_m: must be finite and positive");
  if (!IsFinitePositive(p.max_range_m()))
    throw Error("evidence.max_range_m: must be finite and positive");
  if (p.max_range_m() / p.cell_size_m() > kMaxCellsPerBeam)
    throw Error("evidence.max_range_m: at most " + std::to_string(kMaxCellsPerBeam) +
                " cells of evidence.cell_size_m");
  if (!(p.max_belief() > 0.0 && p.max_belief() < 1.0))
    throw Error("evidence.max_belief: must be in (0, 1)");
  if (!IsFinitePositive(p.reliability_distance_m()))
    throw Error("evidence.reliability_distance_m: must be finite and positive");
  if (!(p.count_above() >= 0.0 && p.count_above() < 1.0))
    throw Error("evidence.count_above: must be in [0, 1)");
  if (p.beam_stride() == 0) throw Error("evidence.beam_stride: must be at least 1");
}

std::uint32_t EvidenceUnits(double mass) {
  const double units = std::round(-std::log1p(-mass) / kEvidenceUnit);
  return static_cast<std::uint32_t>(
      std::clamp(units, 1.0, static_cast<double>(std::numeric_limits<std::uint32_t>::max())));
}

double ReadingMass(const proto::EvidenceGridParams& params, double distance_m) {
  return params.max_belief() * std::exp(-distance_m / params.reliability_distance_m());
}

CellBeliefs EvidenceScorer::Beliefs(std::uint32_t occupied_units, std::uint32_t empty_units) const {
  if (occupied_units >= empty_units) {
    const DempsterTerms t = Combine(occupied_units, empty_units);
    return {t.hi_belief, t.lo_belief};
  }
  const DempsterTerms t = Combine(empty_units, occupied_units);
  return {t.lo_belief, t.hi_belief};
}

CellScore EvidenceScorer::Score(std::uint32_t occupied_units, std::uint32_t empty_units) const {
  if ((occupied_units | empty_units) == 0) return {};
  const bool occupied_more = occupied_units >= empty_units;
  const DempsterTerms t =
      occupied_more ? Combine(occupied_units, empty_units) : Combine(empty_units, occupied_units);
  const double occupied = occupied_more ? t.hi_belief : t.lo_belief;
  const double empty = occupied_more ? t.lo_belief : t.hi_belief;
  return {static_cast<std::int64_t>(t.lo_belief / kConsistencyUnit + 0.5), occupied > count_above_,
          empty > count_above_};
}

EmptyWeights::EmptyWeights(const proto::EvidenceGridParams& params, double cell_size_m) {
  const double bin_m = cell_size_m / kEvidenceBinsPerCell;
  const auto bins = static_cast<std::size_t>(std::ceil(params.max_range_m() / bin_m)) + 1;
  units_.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) {
    units_[i] = EvidenceUnits(ReadingMass(params, (static_cast<double>(i) + 0.5) * bin_m));
  }
}

}  // namespace evoslam
