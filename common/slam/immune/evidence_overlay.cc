#include "common/slam/immune/evidence_overlay.h"

#include "common/slam/immune/evidence_trace.h"

namespace evoslam {

template <bool kAdd>
struct EvidenceOverlay::Writer {
  Change* changes;
  std::vector<std::uint32_t>& touched;

  Change& At(std::size_t cell) {
    Change& c = changes[cell];
    if ((c.occupied | c.empty) == 0) touched.push_back(static_cast<std::uint32_t>(cell));
    return c;
  }
  void Empty(std::size_t cell, std::uint32_t units) { At(cell).empty += kAdd ? units : 0u - units; }
  void Occupied(std::size_t cell, std::uint32_t units) {
    At(cell).occupied += kAdd ? units : 0u - units;
  }
};

EvidenceOverlay::EvidenceOverlay(const EvidenceGrid& base)
    : base_(&base), changes_(base.geometry().cell_count()) {}

EvidenceTotals EvidenceOverlay::ScoreTotals(std::span<const PlacedScan> removed,
                                            std::span<const PlacedScan> added) {
  const EvidenceGrid& base = *base_;
  Writer<false> take{changes_.data(), touched_};
  for (const PlacedScan& s : removed) {
    evidence_trace::TraceScan(base.geometry(), base.empty_weights(), s, take);
  }
  Writer<true> put{changes_.data(), touched_};
  for (const PlacedScan& s : added) {
    evidence_trace::TraceScan(base.geometry(), base.empty_weights(), s, put);
  }
  EvidenceTotals totals = base.totals();
  const EvidenceScorer& scorer = base.scorer();
  for (const std::uint32_t cell : touched_) {
    Change& c = changes_[cell];
    if ((c.occupied | c.empty) == 0) continue;
    const std::uint32_t occupied = base.occupied_units(cell);
    const std::uint32_t empty = base.empty_units(cell);
    totals.Add(scorer.Score(occupied, empty), -1);
    totals.Add(scorer.Score(occupied + c.occupied, empty + c.empty), 1);
    c = {};
  }
  touched_.clear();
  return totals;
}

}  // namespace evoslam
