#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_OVERLAY_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_OVERLAY_H_

#include <cstdint>
#include <span>
#include <vector>

#include "common/slam/immune/evidence_grid.h"
#include "common/slam/immune/evidence_scan.h"

namespace evoslam {

// Scores moved scans against a fixed base grid without changing it: Score gives the objectives the
// base would have with `removed` taken out and `added` put in, equal to the bit to those of a grid
// built with that change. It costs in proportion to those scans, not to the grid.
//
// Keeps a change per cell of the base (8 bytes a cell, allocated once) and the cells a call
// touched, so a call after the first allocates nothing. One overlay per thread: the base is only
// read, so many overlays may share it while nothing changes it.
class EvidenceOverlay {
 public:
  explicit EvidenceOverlay(const EvidenceGrid& base);

  // `removed` must be in the base at these poses; scans must be prepared with the base's params.
  EvidenceObjectives Score(std::span<const PlacedScan> removed, std::span<const PlacedScan> added) {
    return ScoreTotals(removed, added).objectives();
  }
  EvidenceTotals ScoreTotals(std::span<const PlacedScan> removed,
                             std::span<const PlacedScan> added);

  const EvidenceGrid& base() const { return *base_; }

 private:
  // The change of a cell's sums, modulo 2^32 as the sums themselves.
  struct Change {
    std::uint32_t occupied = 0;
    std::uint32_t empty = 0;
  };
  template <bool kAdd>
  struct Writer;

  const EvidenceGrid* base_;
  std::vector<Change> changes_;
  // The cells whose change went from nothing to something; a cell may be here twice if its change
  // cancelled and came back, and is scored once, as its change is zeroed when it is.
  std::vector<std::uint32_t> touched_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_OVERLAY_H_
