#include "common/slam/immune/evidence_overlay.h"

#include <algorithm>
#include <cmath>

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
  void Apply(std::size_t cell, const Change& change) {
    Change& c = At(cell);
    c.occupied += change.occupied;
    c.empty += change.empty;
  }
};

namespace {

// The box of grid cells that the beams of some scans can reach, grown into `box`: around each
// laser, its longest beam and two cells for the rounding of the walk. Scans whose pose is not
// finite reach nothing.
template <typename Box>
void GrowEvidenceReach(const GridGeometry& grid, std::span<const PlacedScan> scans, Box& box) {
  const auto cell = [](double v, int n) {
    return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
  };
  for (const PlacedScan& s : scans) {
    const double cx = grid.CellX(s.pose.x());
    const double cy = grid.CellY(s.pose.y());
    if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(s.pose.theta())) continue;
    const double r = s.scan->max_range_m() / grid.resolution() + 2.0;
    const Box reach{cell(cx - r, grid.width()), cell(cy - r, grid.height()),
                    cell(cx + r, grid.width()), cell(cy + r, grid.height())};
    if (box.x0 > box.x1) {
      box = reach;
      continue;
    }
    box = {std::min(box.x0, reach.x0), std::min(box.y0, reach.y0), std::max(box.x1, reach.x1),
           std::max(box.y1, reach.y1)};
  }
}

evidence_trace::CellNumbering NumberingOf(int x0, int y0, int x1) {
  return {x0, y0, static_cast<std::ptrdiff_t>(x1 - x0 + 1)};
}

}  // namespace

void EvidenceOverlay::Cover(const Box& box) {
  const auto cells =
      static_cast<std::size_t>(box.x1 - box.x0 + 1) * static_cast<std::size_t>(box.y1 - box.y0 + 1);
  if (changes_.size() < cells) changes_.resize(cells);
}

EvidenceTotals EvidenceOverlay::ScoreTotals(std::span<const PlacedScan> removed,
                                            std::span<const PlacedScan> added) {
  SetRemoved(removed);
  return ScoreAddedTotals(added);
}

void EvidenceOverlay::SetRemoved(std::span<const PlacedScan> removed) {
  const EvidenceGrid& base = *base_;
  const GridGeometry& grid = base.geometry();
  removed_.clear();
  removed_box_ = {};
  GrowEvidenceReach(grid, removed, removed_box_);
  const Box& box = removed_box_;
  if (box.x0 > box.x1) return;
  Cover(box);
  const evidence_trace::CellNumbering numbering = NumberingOf(box.x0, box.y0, box.x1);
  Writer<false> take{changes_.data(), touched_};
  for (const PlacedScan& s : removed) {
    evidence_trace::TraceScan(grid, base.empty_weights(), numbering, s, take);
  }
  const auto stride = static_cast<std::size_t>(numbering.stride);
  for (const std::uint32_t local : touched_) {
    Change& c = changes_[local];
    if ((c.occupied | c.empty) == 0) continue;
    removed_.push_back(
        {box.x0 + static_cast<int>(local % stride), box.y0 + static_cast<int>(local / stride), c});
    c = {};
  }
  touched_.clear();
}

EvidenceTotals EvidenceOverlay::ScoreAddedTotals(std::span<const PlacedScan> added) {
  const EvidenceGrid& base = *base_;
  const GridGeometry& grid = base.geometry();
  Box box = removed_box_;
  GrowEvidenceReach(grid, added, box);
  if (box.x0 > box.x1) return base.totals();
  Cover(box);
  const evidence_trace::CellNumbering numbering = NumberingOf(box.x0, box.y0, box.x1);
  const auto stride = static_cast<std::size_t>(numbering.stride);
  Writer<true> put{changes_.data(), touched_};
  for (const CellChange& r : removed_) {
    put.Apply(
        static_cast<std::size_t>(r.y - box.y0) * stride + static_cast<std::size_t>(r.x - box.x0),
        r.change);
  }
  for (const PlacedScan& s : added) {
    evidence_trace::TraceScan(grid, base.empty_weights(), numbering, s, put);
  }

  EvidenceTotals totals = base.totals();
  const EvidenceScorer& scorer = base.scorer();
  for (const std::uint32_t local : touched_) {
    Change& c = changes_[local];
    if ((c.occupied | c.empty) == 0) continue;
    const std::size_t cell = grid.Index(box.x0 + static_cast<int>(local % stride),
                                        box.y0 + static_cast<int>(local / stride));
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
