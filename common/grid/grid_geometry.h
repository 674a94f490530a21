#ifndef EVOSLAM_COMMON_GRID_GRID_GEOMETRY_H_
#define EVOSLAM_COMMON_GRID_GRID_GEOMETRY_H_

#include <Eigen/Core>
#include <cstddef>
#include <optional>

namespace evoslam {

// Where a grid of square cells lies in the world. Cell (x, y) covers
// [origin + (x, y) * resolution, origin + (x + 1, y + 1) * resolution); x grows with world x, y
// with world y. Cells are numbered row by row from the lowest y: index y * width + x.
//
// The world-to-cell conversions are inline and divide by the resolution: the searches convert
// every end point of every candidate pose, and their results hang on these exact operations.
class GridGeometry {
 public:
  // No cells, so that every point lies outside; for a grid with nothing to cover.
  GridGeometry() = default;
  // Throws evoslam::Error for a non-positive or non-finite resolution, a non-finite origin or a
  // non-positive size.
  GridGeometry(double resolution, const Eigen::Vector2d& origin, int width, int height);

  double resolution() const { return resolution_; }
  const Eigen::Vector2d& origin() const { return origin_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t cell_count() const {
    return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  }
  // The world corner opposite the origin.
  Eigen::Vector2d max_corner() const;

  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  // The index of cell (x, y), which must lie in the grid.
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
  }

  // A world coordinate in cells from the origin, not floored: (world - origin) / resolution. The
  // scalar forms serve loops that transform a point's coordinates one at a time.
  double CellX(double world_x) const { return (world_x - origin_.x()) / resolution_; }
  double CellY(double world_y) const { return (world_y - origin_.y()) / resolution_; }
  Eigen::Vector2d ToCells(const Eigen::Vector2d& point) const {
    return (point - origin_) / resolution_;
  }
  // Whether a position in cells (as ToCells gives) lies on the grid. floor(v) lies in [0, n)
  // exactly when v does, and there truncation is the floor, so no call to floor is needed; NaN
  // fails every comparison and lies outside.
  bool ContainsCells(double x, double y) const {
    return x >= 0 && y >= 0 && x < width_ && y < height_;
  }

  // The cell holding a world point; nullopt outside the grid or for a point not finite.
  std::optional<Eigen::Vector2i> WorldToCell(const Eigen::Vector2d& point) const {
    const Eigen::Vector2d cell = ToCells(point);
    if (!ContainsCells(cell.x(), cell.y())) return std::nullopt;
    return Eigen::Vector2i(static_cast<int>(cell.x()), static_cast<int>(cell.y()));
  }
  // The index of the cell holding a world point; nullopt outside the grid.
  std::optional<std::size_t> CellIndex(const Eigen::Vector2d& point) const {
    const auto cell = WorldToCell(point);
    if (!cell) return std::nullopt;
    return Index(cell->x(), cell->y());
  }
  // The world position of a cell's centre.
  Eigen::Vector2d CellToWorld(int x, int y) const {
    return origin_ + resolution_ * Eigen::Vector2d(x + 0.5, y + 0.5);
  }

 private:
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // first: its 16-byte alignment pads nothing
  double resolution_ = 1.0;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_GRID_GEOMETRY_H_
