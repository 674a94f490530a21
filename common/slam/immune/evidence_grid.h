#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_GRID_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_GRID_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/grid/grid_geometry.h"
#include "common/grid/occupancy_grid.h"
#include "common/slam/immune/evidence_model.h"
#include "common/slam/immune/evidence_scan.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// Paper 004's objectives of a map (§2, eqs. 1-3), all minimised. See evidence_model.h for how they
// are read.
struct EvidenceObjectives {
  double consistency = 0;     // f1: the contradiction min(occ, emp) summed over the cells
  std::int64_t occupied = 0;  // f2: cells with occ > count_above
  std::int64_t empty = 0;     // f3: cells with emp > count_above
  bool operator==(const EvidenceObjectives&) const = default;
};

// The objectives as integers: f1 in kConsistencyUnit. Grids and overlays keep these, so that
// totals reached by different routes compare equal to the bit.
struct EvidenceTotals {
  std::int64_t consistency = 0;
  std::int64_t occupied = 0;
  std::int64_t empty = 0;

  void Add(const CellScore& score, std::int64_t sign) {
    consistency += sign * score.consistency;
    occupied += sign * static_cast<std::int64_t>(score.occupied);
    empty += sign * static_cast<std::int64_t>(score.empty);
  }
  EvidenceObjectives objectives() const {
    return {static_cast<double>(consistency) * kConsistencyUnit, occupied, empty};
  }
};

// A Dempster-Shafer evidence grid over a GridGeometry: per cell the integer sums of its occupied
// and empty readings (evidence_model.h), and the objectives over all cells, kept up to date as
// scans come and go. Readings that fall outside the geometry are ignored. Const methods may run
// concurrently.
class EvidenceGrid {
 public:
  static constexpr long long kMaxCells = OccupancyGrid::kMaxCells;

  // No scans. Throws evoslam::Error for invalid params or a geometry of no cells or more than
  // kMaxCells. The geometry's resolution is the cell size; params.cell_size_m is not read.
  EvidenceGrid(const GridGeometry& geometry, const proto::EvidenceGridParams& params);

  // Adds a scan's readings. Scans must be prepared with this grid's params.
  void Add(const PlacedScan& scan) { Add(std::span(&scan, 1)); }
  // Takes back what Add(scan) added, exactly; the scan at the same pose must be in the grid.
  void Remove(const PlacedScan& scan) { Remove(std::span(&scan, 1)); }
  // The same for many scans at once; the objectives are then recounted once. The state and the
  // objectives are those of adding or removing the scans one by one, in any order.
  void Add(std::span<const PlacedScan> scans);
  void Remove(std::span<const PlacedScan> scans);

  EvidenceObjectives objectives() const { return totals_.objectives(); }
  const EvidenceTotals& totals() const { return totals_; }

  // A cell's sums, in kEvidenceUnit, and its beliefs, by cell index (which must lie in the grid).
  std::uint32_t occupied_units(std::size_t cell) const { return occupied_[cell]; }
  std::uint32_t empty_units(std::size_t cell) const { return empty_[cell]; }
  CellBeliefs beliefs(std::size_t cell) const {
    return scorer_.Beliefs(occupied_[cell], empty_[cell]);
  }
  double occupied_belief(std::size_t cell) const { return beliefs(cell).occupied; }
  double empty_belief(std::size_t cell) const { return beliefs(cell).empty; }
  // What the cell adds to the objectives.
  CellScore score(std::size_t cell) const { return scorer_.Score(occupied_[cell], empty_[cell]); }

  const GridGeometry& geometry() const { return geometry_; }
  const proto::EvidenceGridParams& params() const { return params_; }
  const EmptyWeights& empty_weights() const { return weights_; }
  const EvidenceScorer& scorer() const { return scorer_; }

 private:
  template <bool kAdd>
  void Change(std::span<const PlacedScan> scans);
  template <bool kAdd>
  void ChangeTracked(std::span<const PlacedScan> scans);
  void Recount();

  GridGeometry geometry_;
  proto::EvidenceGridParams params_;
  EmptyWeights weights_;
  EvidenceScorer scorer_;
  std::vector<std::uint32_t> occupied_;
  std::vector<std::uint32_t> empty_;
  EvidenceTotals totals_;
  // While a change is traced: a bit per cell it has touched, and those cells, whose old score
  // leaves the totals at the first touch and whose new one joins them at the end.
  std::vector<std::uint64_t> touched_bits_;
  std::vector<std::uint32_t> touched_;
};

// The geometry of a grid that holds every scan at these poses: the laser positions grown by
// max_range_m and by `margin_m` (room for poses a search moves), in cells of cell_size_m. Throws
// evoslam::Error for no scans, a pose that is not finite, invalid params or more than
// EvidenceGrid::kMaxCells cells.
inline constexpr double kEvidenceGeometryMargin = 1.0;
GridGeometry EvidenceGeometryFor(std::span<const PlacedScan> scans,
                                 const proto::EvidenceGridParams& params,
                                 double margin_m = kEvidenceGeometryMargin);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_GRID_H_
