#ifndef EVOSLAM_COMMON_GRID_HIT_COUNT_GRID_H_
#define EVOSLAM_COMMON_GRID_HIT_COUNT_GRID_H_

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/grid/grid_geometry.h"
#include "common/grid/tiled_counts.h"
#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"
#include "common/transform/pose2_frame.h"

namespace evoslam {

// Two sets of HitCountGrid cell indices, to count the distinct cells a scan or a stretch of scans
// falls in without sorting its points. Both: Insert (true when the cell was not there yet) and
// Contains cost O(1), Clear costs the cells inserted.
//
// CellSet, for a few cells (a scan): open addressing in a table kept at most half full, so it
// costs its cells' memory, not the grid's.
class CellSet {
 public:
  // Room for `expected` cells before the table has to grow.
  explicit CellSet(std::size_t expected = 0);

  bool Insert(std::size_t cell) {
    const std::uint32_t key = Key(cell);
    std::size_t slot = Home(key);
    for (; table_[slot] != 0; slot = (slot + 1) & mask_) {
      if (table_[slot] == key) return false;
    }
    if (2 * (used_.size() + 1) > table_.size()) {
      Grow();
      return Insert(cell);
    }
    table_[slot] = key;
    used_.push_back(slot);
    return true;
  }
  bool Contains(std::size_t cell) const {
    const std::uint32_t key = Key(cell);
    for (std::size_t slot = Home(key); table_[slot] != 0; slot = (slot + 1) & mask_) {
      if (table_[slot] == key) return true;
    }
    return false;
  }
  std::size_t size() const { return used_.size(); }
  void Clear();

 private:
  // Cell + 1, so that 0 marks an empty slot (HitCountGrid::kMaxCells keeps it in 32 bits).
  static std::uint32_t Key(std::size_t cell) { return static_cast<std::uint32_t>(cell + 1); }
  // Fibonacci hashing: a scan's cells lie along walls, which the low bits alone would crowd into
  // runs of neighbouring slots.
  std::size_t Home(std::uint32_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift_);
  }
  void Grow();

  std::vector<std::uint32_t> table_;  // cell + 1 per slot, 0 when empty; a power of two of them
  std::vector<std::size_t> used_;     // the slots holding a cell
  std::size_t mask_ = 0;
  int shift_ = 64;
};

// GridCellSet, for many (a stretch of scans, tens of thousands of end points): a bit per cell of
// the grid. Neighbouring cells share a word, so the points of a wall touch few words where a hash
// table would scatter them (docs/benchmarks.md), while making one for a single scan would cost
// more than its lookups.
class GridCellSet {
 public:
  explicit GridCellSet(std::size_t grid_cells) : bits_((grid_cells + 63) / 64, 0) {}

  bool Insert(std::size_t cell) {
    std::uint64_t& word = bits_[cell / 64];
    const std::uint64_t old = word;
    const std::uint64_t bit = std::uint64_t{1} << (cell % 64);
    word = old | bit;
    // A word's first cell records it for Clear: rare, a branch the predictor gets right. Whether
    // the cell is new is a coin toss to it, so that is counted without a branch.
    if (old == 0) words_.push_back(cell / 64);
    return (old & bit) == 0;
  }
  bool Contains(std::size_t cell) const { return (bits_[cell / 64] >> (cell % 64)) & 1; }
  std::size_t size() const;
  void Clear();

 private:
  std::vector<std::uint64_t> bits_;
  std::vector<std::size_t> words_;  // the words set, which Clear zeroes
};

// The map of paper 002 (§3.1): each cell counts how many times an obstacle was observed in it.
// The grid keeps the sum of all counts and the number of cells above zero as it changes, so the
// paper's whole-map score (eq. 6: mean observations per occupied cell) costs nothing to read;
// scores over a window (eqs. 1 and 2) cost the window's cells. The cells are a GridGeometry's.
// The counts are kept in tiles (TiledCounts), so a grid's memory grows with the area its scans
// cover, not with the whole grid; only its bits of occupied cells cover the whole grid.
class HitCountGrid {
 public:
  static constexpr long long kMaxCells = 1LL << 28;

  // All cells zero. Throws evoslam::Error for a non-positive or non-finite resolution, a
  // non-finite origin, a non-positive size, or more than kMaxCells cells.
  HitCountGrid(double resolution, const Eigen::Vector2d& origin, int width, int height);

  const GridGeometry& geometry() const { return geometry_; }
  double resolution() const { return geometry_.resolution(); }
  const Eigen::Vector2d& origin() const { return geometry_.origin(); }
  int width() const { return geometry_.width(); }
  int height() const { return geometry_.height(); }

  // The cell holding a world point; nullopt outside the grid or for a point not finite. Inline,
  // as the searches look up every end point of every candidate.
  std::optional<Eigen::Vector2i> WorldToCell(const Eigen::Vector2d& point) const {
    return geometry_.WorldToCell(point);
  }
  // The index of the cell holding a world point (row-major: y * width + x), for callers that
  // gather cells; nullopt outside the grid.
  std::optional<std::size_t> CellIndex(const Eigen::Vector2d& point) const {
    return geometry_.CellIndex(point);
  }
  // Throws std::out_of_range outside the grid.
  std::uint32_t count(int x, int y) const;
  // The count of a cell by its index; throws std::out_of_range for an index past the grid.
  std::uint32_t count(std::size_t index) const;
  // Whether a cell's count is above zero, by its index (which must lie in the grid).
  bool occupied(std::size_t index) const {
    return (occupied_bits_[index / 64] >> (index % 64)) & 1;
  }

  // Ray coverage, our addition to 002's map. Once on, AddScan also counts, in every cell a beam
  // crosses on its way to its return (or to the laser's range where it returns nothing), the
  // rays that crossed it, and takes them back with the scan, so that the coverage, like the
  // counts, is that of the scans at the poses they were last added at. Turn it on before adding
  // scans; it costs a bit per cell and four bytes per cell of the tiles the rays cross.
  void TrackRays();
  bool tracks_rays() const { return !crossed_bits_.empty(); }
  // Whether a ray crosses a cell, by its index (which must lie in the grid); false without ray
  // coverage.
  bool crossed(std::size_t index) const {
    return !crossed_bits_.empty() && ((crossed_bits_[index / 64] >> (index % 64)) & 1);
  }
  // A cell on the edge of what the rays have seen: neither crossed nor occupied, and next to a
  // cell that is crossed and not occupied (of its eight neighbours). Such are the first cells of
  // a wall a corner hid from the scans so far, or of one just past the laser's reach, and the
  // gaps grazing beams leave between their hits along a wall. False without ray coverage, and
  // on the grid's border.
  bool Frontier(std::size_t index) const;

  // Adds `delta` observations at a world point (a negative delta takes them back; a count never
  // goes below zero). Returns false, changing nothing, for a point outside the grid.
  bool Add(const Eigen::Vector2d& point, int delta = 1);
  // Adds one observation at the end point of every return of `scan` seen by the laser at `pose`
  // (or takes them back with delta -1). Returns how many end points fell outside the grid.
  std::size_t AddScan(const LaserScan& scan, const Pose2& pose, int delta = 1);

  // What adding `points` seen from `frame` would add, the grid left as it is: to `inside` the
  // points that fall in it, to `fresh` the cells they would make occupied. `cells` (a CellSet or
  // a GridCellSet) receives the cells hit, and a cell already there is not counted again, so that
  // several scans can be counted as one insertion (clear it between insertions).
  struct Insertion {
    std::uint64_t inside = 0;
    std::uint64_t fresh = 0;
  };
  // With `frontier_free`, a point on a Frontier cell makes no cell occupied: nothing the rays
  // saw says there is no obstacle there.
  template <typename Cells>
  void CountInsertion(const Pose2Frame& frame, std::span<const Eigen::Vector2d> points,
                      Cells& cells, Insertion& sums, bool frontier_free = false) const;

  std::uint64_t total() const { return total_; }        // the sum of all counts
  std::uint64_t occupied() const { return occupied_; }  // cells whose count is above zero
  // Eq. 6 over the whole grid: total / occupied, 0 for an empty grid.
  double MeanPerOccupied() const;

  // The same two sums over the cells [x0, x1) x [y0, y1), clipped to the grid.
  struct WindowSums {
    std::uint64_t total = 0;
    std::uint64_t occupied = 0;
  };
  WindowSums Window(int x0, int y0, int x1, int y1) const;

  // The memory the grid keeps: its tiles of counts and crossings, and its bits.
  std::size_t bytes() const;

 private:
  GridGeometry geometry_;
  TiledCounts counts_;
  // A bit per cell, set while its count is above zero: what scoring an insertion asks of every
  // cell, in a 32nd of the memory, so that it stays in cache.
  std::vector<std::uint64_t> occupied_bits_;
  // Once TrackRays is on: the rays crossing each cell, and a bit per cell set while that is above
  // zero (read for every return the local search scores).
  TiledCounts crossings_;
  std::vector<std::uint64_t> crossed_bits_;
  // Adds `delta` to the crossings of the cells a ray from `from` to `to` crosses, the cell of
  // `to` left out.
  void AddCrossings(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int delta);
  std::uint64_t total_ = 0;
  std::uint64_t occupied_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_HIT_COUNT_GRID_H_
