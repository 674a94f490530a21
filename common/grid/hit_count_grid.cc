#include "common/grid/hit_count_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/util/error.h"

namespace evoslam {

HitCountGrid::HitCountGrid(double resolution, const Eigen::Vector2d& origin, int width, int height)
    : resolution_(resolution), origin_(origin), width_(width), height_(height) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("hit count grid: resolution must be positive and finite");
  }
  if (!origin.allFinite()) throw Error("hit count grid: origin must be finite");
  if (width <= 0 || height <= 0) throw Error("hit count grid: width and height must be positive");
  if (static_cast<long long>(width) * height > kMaxCells) {
    throw Error("hit count grid: " + std::to_string(width) + " x " + std::to_string(height) +
                " cells is over the limit of " + std::to_string(kMaxCells));
  }
  counts_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
}

std::optional<Eigen::Vector2i> HitCountGrid::WorldToCell(const Eigen::Vector2d& point) const {
  const Eigen::Vector2d cell = (point - origin_) / resolution_;
  if (!cell.allFinite()) return std::nullopt;
  const double x = std::floor(cell.x()), y = std::floor(cell.y());
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return std::nullopt;
  return Eigen::Vector2i(static_cast<int>(x), static_cast<int>(y));
}

std::optional<std::size_t> HitCountGrid::CellIndex(const Eigen::Vector2d& point) const {
  const auto cell = WorldToCell(point);
  if (!cell) return std::nullopt;
  return Index(cell->x(), cell->y());
}

std::uint32_t HitCountGrid::count(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) {
    throw std::out_of_range("hit count grid: cell (" + std::to_string(x) + ", " +
                            std::to_string(y) + ") is outside the grid");
  }
  return counts_[Index(x, y)];
}

bool HitCountGrid::Add(const Eigen::Vector2d& point, int delta) {
  const auto index = CellIndex(point);
  if (!index) return false;
  std::uint32_t& c = counts_[*index];
  const std::uint32_t before = c;
  if (delta >= 0) {
    c += static_cast<std::uint32_t>(delta);
  } else {
    c -= std::min(c, static_cast<std::uint32_t>(-static_cast<long long>(delta)));
  }
  total_ = total_ - before + c;
  occupied_ = occupied_ - (before > 0) + (c > 0);
  return true;
}

std::size_t HitCountGrid::AddScan(const LaserScan& scan, const Pose2& pose, int delta) {
  std::size_t outside = 0;
  for (const Eigen::Vector2d& p : ReturnPoints(scan)) outside += !Add(pose * p, delta);
  return outside;
}

double HitCountGrid::MeanPerOccupied() const {
  return occupied_ > 0 ? static_cast<double>(total_) / static_cast<double>(occupied_) : 0.0;
}

HitCountGrid::WindowSums HitCountGrid::Window(int x0, int y0, int x1, int y1) const {
  WindowSums sums;
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_);
  y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint32_t c = counts_[Index(x, y)];
      sums.total += c;
      sums.occupied += c > 0;
    }
  }
  return sums;
}

}  // namespace evoslam
