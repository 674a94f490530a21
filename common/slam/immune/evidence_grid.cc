#include "common/slam/immune/evidence_grid.h"

#include <cmath>
#include <string>

#include "common/slam/immune/evidence_trace.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Writes readings straight into the sums, for changes so large that recounting every cell costs
// less than keeping track of the cells they touch. Unsigned sums: taking back wraps as adding did.
template <bool kAdd>
struct EvidenceSumWriter {
  std::uint32_t* occupied;
  std::uint32_t* empty;

  void Empty(std::size_t cell, std::uint32_t units) { empty[cell] += kAdd ? units : 0u - units; }
  void Occupied(std::size_t cell, std::uint32_t units) {
    occupied[cell] += kAdd ? units : 0u - units;
  }
};

// Writes readings into the sums and takes each cell's old score out of the totals at its first
// touch, noting the cell so that its new score can join them once all readings are in.
template <bool kAdd>
struct EvidenceTrackedWriter {
  std::uint32_t* occupied;
  std::uint32_t* empty;
  std::uint64_t* touched_bits;
  std::vector<std::uint32_t>& touched;
  const EvidenceScorer& scorer;
  EvidenceTotals& totals;

  void Touch(std::size_t cell) {
    std::uint64_t& word = touched_bits[cell / 64];
    const std::uint64_t bit = std::uint64_t{1} << (cell % 64);
    if (word & bit) return;
    word |= bit;
    touched.push_back(static_cast<std::uint32_t>(cell));
    totals.Add(scorer.Score(occupied[cell], empty[cell]), -1);
  }
  void Empty(std::size_t cell, std::uint32_t units) {
    Touch(cell);
    empty[cell] += kAdd ? units : 0u - units;
  }
  void Occupied(std::size_t cell, std::uint32_t units) {
    Touch(cell);
    occupied[cell] += kAdd ? units : 0u - units;
  }
};

}  // namespace

EvidenceGrid::EvidenceGrid(const GridGeometry& geometry, const proto::EvidenceGridParams& params)
    : geometry_(geometry),
      params_((ValidateEvidenceGridParams(params), params)),
      weights_(params, geometry.resolution()),
      scorer_(params.count_above()) {
  const long long cells = static_cast<long long>(geometry.width()) * geometry.height();
  if (cells <= 0 || cells > kMaxCells) {
    throw Error("evidence grid: " + std::to_string(cells) + " cells; from 1 to " +
                std::to_string(kMaxCells));
  }
  occupied_.assign(geometry.cell_count(), 0);
  empty_.assign(geometry.cell_count(), 0);
  touched_bits_.assign((geometry.cell_count() + 63) / 64, 0);
}

void EvidenceGrid::Add(std::span<const PlacedScan> scans) { Change<true>(scans); }

void EvidenceGrid::Remove(std::span<const PlacedScan> scans) { Change<false>(scans); }

template <bool kAdd>
void EvidenceGrid::Change(std::span<const PlacedScan> scans) {
  double beam_cells = 0.0;
  for (const PlacedScan& s : scans) beam_cells += s.scan->total_range_m();
  beam_cells /= geometry_.resolution();
  // Tracking a cell costs about what scoring one does; past a grid's worth of beam cells most
  // cells are touched anyway.
  if (beam_cells < static_cast<double>(geometry_.cell_count())) {
    ChangeTracked<kAdd>(scans);
    return;
  }
  EvidenceSumWriter<kAdd> writer{occupied_.data(), empty_.data()};
  const evidence_trace::CellNumbering numbering{.stride = geometry_.width()};
  for (const PlacedScan& s : scans) {
    evidence_trace::TraceScan(geometry_, weights_, numbering, s, writer);
  }
  Recount();
}

template <bool kAdd>
void EvidenceGrid::ChangeTracked(std::span<const PlacedScan> scans) {
  EvidenceTrackedWriter<kAdd> writer{occupied_.data(), empty_.data(), touched_bits_.data(),
                                     touched_,         scorer_,       totals_};
  const evidence_trace::CellNumbering numbering{.stride = geometry_.width()};
  for (const PlacedScan& s : scans) {
    evidence_trace::TraceScan(geometry_, weights_, numbering, s, writer);
  }
  for (const std::uint32_t cell : touched_) {
    totals_.Add(scorer_.Score(occupied_[cell], empty_[cell]), 1);
    touched_bits_[cell / 64] = 0;
  }
  touched_.clear();
}

void EvidenceGrid::Recount() {
  totals_ = {};
  for (std::size_t cell = 0; cell < occupied_.size(); ++cell) {
    if ((occupied_[cell] | empty_[cell]) != 0) totals_.Add(score(cell), 1);
  }
}

GridGeometry EvidenceGeometryFor(std::span<const PlacedScan> scans,
                                 const proto::EvidenceGridParams& params, double margin_m) {
  ValidateEvidenceGridParams(params);
  if (scans.empty()) throw Error("evidence grid: no scans to size a grid for");
  Eigen::Vector2d lo = scans.front().pose.translation();
  Eigen::Vector2d hi = lo;
  for (const PlacedScan& s : scans) {
    const Eigen::Vector2d p = s.pose.translation();
    if (!p.allFinite() || !std::isfinite(s.pose.theta())) {
      throw Error("evidence grid: a scan's pose is not finite");
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double reach = params.max_range_m() + margin_m;
  const double res = params.cell_size_m();
  const Eigen::Vector2d origin = lo.array() - reach;
  // One cell more than the extent needs, so that a point exactly on the far edge is inside; in
  // doubles, as a wild extent can be beyond any integer.
  const Eigen::Vector2d cells = ((hi.array() + reach - origin.array()) / res).floor() + 1.0;
  if (cells.x() * cells.y() > static_cast<double>(EvidenceGrid::kMaxCells)) {
    throw Error("evidence grid: the scans span " + std::to_string(hi.x() - lo.x()) + " x " +
                std::to_string(hi.y() - lo.y()) + " m, over " +
                std::to_string(EvidenceGrid::kMaxCells) + " cells of evidence.cell_size_m");
  }
  return GridGeometry(res, origin, static_cast<int>(cells.x()), static_cast<int>(cells.y()));
}

}  // namespace evoslam
