#ifndef EVOSLAM_COMMON_GRID_OCCUPANCY_GRID_H_
#define EVOSLAM_COMMON_GRID_OCCUPANCY_GRID_H_

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/grid/grid_geometry.h"
#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"

namespace evoslam {

enum class CellState { kUnknown, kFree, kOccupied };

// Inverse sensor model. A cell's log-odds is derived from its counts as
//   hits * logit(kHitProbability) + misses * logit(kMissProbability)
// over a prior of 0.5, so a grid does not depend on the order its scans were inserted in.
// A hit weighs as much as three misses, as in GMapping's rule (occupied once a quarter of the
// beams reaching a cell end there): rays grazing a corridor wall from far off cross its row of
// cells, and misses worth half a hit erased walls that only one pass had seen (see
// docs/estimator.md).
inline constexpr double kHitProbability = 0.7;
inline constexpr double kMissProbability = 0.43;
// A cell is occupied above kOccupiedThreshold, free below kFreeThreshold, else unknown.
// With the model above one hit (and no miss) makes a cell occupied, three misses make it free.
inline constexpr double kOccupiedThreshold = 0.65;
inline constexpr double kFreeThreshold = 0.35;
// A beam without a return (a max-range or out-of-range reading) is taken to have crossed free
// space this far, or to range_max if that is shorter: long max-range readings are often beams
// lost on glass or dark surfaces, and clearing all of range_max would erase walls.
inline constexpr double kNoReturnFreeRange = 5.0;

// A 2D occupancy grid over a GridGeometry. Each cell counts the beams that ended in it (hits) and
// that crossed it (misses).
//
// Ray casting leaps through free space by a distance field of the occupied cells, one per
// quadrant of ray directions (a ray heading up and right can only meet cells up and right of
// it, so those are the only ones that limit its leaps), and steps cell by cell only near
// obstacles. The field is built by UpdateDistanceField(); anything that changes cells
// (InsertScan, SetCell) drops it, and CastRay then falls back to a plain cell-by-cell traversal
// with the same result, so it never reads a stale field. FromScans and map loading return grids
// with the field built. Const methods may run concurrently.
class OccupancyGrid {
 public:
  static constexpr long long kMaxCells = 1LL << 26;

  // All cells unknown. Throws evoslam::Error for a non-positive or non-finite resolution, a
  // non-finite origin, a non-positive size, or more than kMaxCells cells.
  OccupancyGrid(double resolution, const Eigen::Vector2d& origin, int width, int height);

  // A grid sized to hold every sensor position and beam end point plus `margin` metres on each
  // side, with every scan inserted at its pose, and the distance field built. poses[i] is the
  // pose of the laser (not the robot base) for scans[i]. Throws evoslam::Error if the spans
  // differ in length or are empty, a pose is not finite, or the parameters are invalid.
  static OccupancyGrid FromScans(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                                 double resolution, double margin);

  // The resolution at which FromScans fits the scans in kMaxCells: `resolution`, or the first of
  // 2, 4, 8, ... times it that does. Throws as FromScans does for bad spans or parameters.
  static double FittingResolution(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                                  double resolution, double margin);

  const GridGeometry& geometry() const { return geometry_; }
  double resolution() const { return geometry_.resolution(); }
  const Eigen::Vector2d& origin() const { return geometry_.origin(); }
  int width() const { return geometry_.width(); }
  int height() const { return geometry_.height(); }
  // World corners of the area the grid covers.
  Eigen::Vector2d min_corner() const { return geometry_.origin(); }
  Eigen::Vector2d max_corner() const { return geometry_.max_corner(); }

  bool Contains(int x, int y) const { return geometry_.Contains(x, y); }
  // The cell holding a world point, or nullopt when the point is outside the grid (or not
  // finite).
  std::optional<Eigen::Vector2i> WorldToCell(const Eigen::Vector2d& point) const {
    return geometry_.WorldToCell(point);
  }
  // The world position of a cell's centre.
  Eigen::Vector2d CellToWorld(int x, int y) const { return geometry_.CellToWorld(x, y); }

  // Per-cell queries; they throw std::out_of_range outside the grid.
  std::uint32_t hits(int x, int y) const { return hits_[Index(x, y)]; }
  std::uint32_t misses(int x, int y) const { return misses_[Index(x, y)]; }
  double log_odds(int x, int y) const;
  double probability(int x, int y) const;
  CellState state(int x, int y) const;
  bool IsOccupied(int x, int y) const { return state(x, y) == CellState::kOccupied; }

  // Traces every beam of `scan` from the laser at `pose` (world frame): the cell a return ends
  // in gains a hit, and the cells a beam crosses gain a miss, except cells that some return of
  // this same scan ends in. Parts of beams outside the grid are ignored. Drops the distance
  // field.
  void InsertScan(const LaserScan& scan, const Pose2& pose);

  // Sets a cell's counts to the fewest that give `state` (unknown: none; occupied: one hit;
  // free: just enough misses). Drops the distance field.
  void SetCell(int x, int y, CellState state);

  // Builds the distance field that makes CastRay fast. O(width * height * log(width)); about
  // 0.13 s for a million cells.
  void UpdateDistanceField();
  bool has_distance_field() const { return !clearance_.empty(); }

  // Distance from `origin` along the ray at `angle` (world frame, radians) to the boundary of the
  // first occupied cell it enters; 0 when origin lies in an occupied cell; max_range when no
  // occupied cell starts within max_range (space outside the grid holds none). A ray that grazes
  // exactly a cell corner or runs exactly along a cell edge may be counted on either side.
  // Returns max_range unchanged when origin or angle is not finite or max_range is not positive.
  double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const;
  // The same along a unit direction, for callers that keep directions and so skip the sine and
  // cosine.
  double CastRay(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                 double max_range) const;

 private:
  // Units of clearance_ (see there).
  static constexpr int kClearanceScale = 32;
  static constexpr std::uint16_t kOccupiedClearance = 0xFFFF;

  std::size_t Index(int x, int y) const;
  bool OccupiedAt(std::size_t index) const;
  void AddHit(std::size_t index);
  void AddMiss(std::size_t index);
  template <bool kUseField>
  double Cast(double ox, double oy, double dx, double dy, double max_range) const;

  GridGeometry geometry_;
  std::vector<std::uint32_t> hits_;
  std::vector<std::uint32_t> misses_;
  // Per cell: how far a ray starting anywhere in the cell may advance without touching an
  // occupied cell, in 1/kClearanceScale cells rounded down (16 bits, to halve the memory the
  // leaps touch), or kOccupiedClearance for an occupied cell. One plane of width * height
  // per quadrant of ray directions, indexed (dx < 0) + 2 * (dy < 0). Empty when stale.
  std::vector<std::uint16_t> clearance_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_OCCUPANCY_GRID_H_
