#ifndef EVOSLAM_COMMON_GRID_HIT_COUNT_GRID_H_
#define EVOSLAM_COMMON_GRID_HIT_COUNT_GRID_H_

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"

namespace evoslam {

// The map of paper 002 (§3.1): each cell counts how many times an obstacle was observed in it.
// The grid keeps the sum of all counts and the number of cells above zero as it changes, so the
// paper's whole-map score (eq. 6: mean observations per occupied cell) costs nothing to read;
// scores over a window (eqs. 1 and 2) cost the window's cells. Cell (x, y) covers
// [origin + (x, y) * resolution, origin + (x + 1, y + 1) * resolution).
class HitCountGrid {
 public:
  static constexpr long long kMaxCells = 1LL << 28;

  // All cells zero. Throws evoslam::Error for a non-positive or non-finite resolution, a
  // non-finite origin, a non-positive size, or more than kMaxCells cells.
  HitCountGrid(double resolution, const Eigen::Vector2d& origin, int width, int height);

  double resolution() const { return resolution_; }
  const Eigen::Vector2d& origin() const { return origin_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // The cell holding a world point; nullopt outside the grid or for a point not finite.
  std::optional<Eigen::Vector2i> WorldToCell(const Eigen::Vector2d& point) const;
  // The index of the cell holding a world point (row-major: y * width + x), for callers that
  // gather cells; nullopt outside the grid.
  std::optional<std::size_t> CellIndex(const Eigen::Vector2d& point) const;
  // Throws std::out_of_range outside the grid.
  std::uint32_t count(int x, int y) const;
  // The count of a cell by its index; throws std::out_of_range for an index past the grid.
  std::uint32_t count(std::size_t index) const { return counts_.at(index); }

  // Adds `delta` observations at a world point (a negative delta takes them back; a count never
  // goes below zero). Returns false, changing nothing, for a point outside the grid.
  bool Add(const Eigen::Vector2d& point, int delta = 1);
  // Adds one observation at the end point of every return of `scan` seen by the laser at `pose`
  // (or takes them back with delta -1). Returns how many end points fell outside the grid.
  std::size_t AddScan(const LaserScan& scan, const Pose2& pose, int delta = 1);

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

 private:
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
  }

  double resolution_;
  Eigen::Vector2d origin_;
  int width_;
  int height_;
  std::vector<std::uint32_t> counts_;
  std::uint64_t total_ = 0;
  std::uint64_t occupied_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_HIT_COUNT_GRID_H_
