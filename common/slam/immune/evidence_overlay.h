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
// A search that scores many candidates for one stretch of scans can take the stretch out once
// (SetRemoved) and then score each candidate's placement of it (ScoreAdded), at about half the
// cost of Score, which traces both.
//
// Keeps the change of every cell in the box the scans reach (8 bytes a cell; the array grows to
// the largest box met and stays), so a call after the first allocates nothing unless its scans
// spread wider. One overlay per thread: the base is only read, so many overlays may share it
// while nothing changes it.
class EvidenceOverlay {
 public:
  explicit EvidenceOverlay(const EvidenceGrid& base) : base_(&base) {}

  // `removed` must be in the base at these poses; scans must be prepared with the base's params.
  EvidenceObjectives Score(std::span<const PlacedScan> removed, std::span<const PlacedScan> added) {
    return ScoreTotals(removed, added).objectives();
  }
  EvidenceTotals ScoreTotals(std::span<const PlacedScan> removed,
                             std::span<const PlacedScan> added);

  // Traces `removed` and keeps what taking it out changes, for the calls of ScoreAdded that
  // follow; the scans need not outlive the call.
  void SetRemoved(std::span<const PlacedScan> removed);
  // The objectives with the scans of the last SetRemoved taken out and `added` put in.
  EvidenceObjectives ScoreAdded(std::span<const PlacedScan> added) {
    return ScoreAddedTotals(added).objectives();
  }
  EvidenceTotals ScoreAddedTotals(std::span<const PlacedScan> added);

  const EvidenceGrid& base() const { return *base_; }

 private:
  // The change of a cell's sums, modulo 2^32 as the sums themselves.
  struct Change {
    std::uint32_t occupied = 0;
    std::uint32_t empty = 0;
  };
  struct CellChange {
    int x = 0;
    int y = 0;
    Change change;
  };
  // Cells [x0, x1] x [y0, y1] of the grid; empty while x0 > x1.
  struct Box {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  template <bool kAdd>
  struct Writer;

  // Makes changes_ cover `box`, row by row from its corner.
  void Cover(const Box& box);

  const EvidenceGrid* base_;
  // Over the box of the current call; all zero between calls.
  std::vector<Change> changes_;
  // The cells (in the box) whose change went from nothing to something; a cell may be here twice
  // if its change cancelled and came back, and is counted once, as its change is zeroed when it is.
  std::vector<std::uint32_t> touched_;
  // What taking out the scans of the last SetRemoved changes, and the box those scans reach.
  std::vector<CellChange> removed_;
  Box removed_box_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_OVERLAY_H_
