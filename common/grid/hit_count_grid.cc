#include "common/grid/hit_count_grid.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "common/util/error.h"

namespace evoslam {

static_assert(HitCountGrid::kMaxCells < (1LL << 32) - 1, "a CellSet key is a cell index + 1");

CellSet::CellSet(std::size_t expected) {
  std::size_t slots = 16;
  while (slots < 2 * expected) slots *= 2;
  table_.assign(slots, 0);
  mask_ = slots - 1;
  shift_ = 64 - std::countr_zero(slots);
  used_.reserve(expected);
}

void CellSet::Clear() {
  for (const std::size_t slot : used_) table_[slot] = 0;
  used_.clear();
}

void CellSet::Grow() {
  std::vector<std::size_t> cells;
  cells.reserve(used_.size());
  for (const std::size_t slot : used_) cells.push_back(table_[slot] - 1);
  *this = CellSet(table_.size());
  for (const std::size_t cell : cells) Insert(cell);
}

void GridCellSet::Clear() {
  for (const std::size_t word : words_) bits_[word] = 0;
  words_.clear();
}

std::size_t GridCellSet::size() const {
  std::size_t n = 0;
  for (const std::size_t word : words_) n += static_cast<std::size_t>(std::popcount(bits_[word]));
  return n;
}

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
  occupied_bits_.assign((counts_.size() + 63) / 64, 0);
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
  if ((before > 0) != (c > 0)) occupied_bits_[*index / 64] ^= std::uint64_t{1} << (*index % 64);
  return true;
}

std::size_t HitCountGrid::AddScan(const LaserScan& scan, const Pose2& pose, int delta) {
  std::size_t outside = 0;
  const Pose2Frame frame(pose);
  for (const Eigen::Vector2d& p : ReturnPoints(scan)) outside += !Add(frame * p, delta);
  return outside;
}

template <typename Cells>
void HitCountGrid::CountInsertion(const Pose2Frame& frame, std::span<const Eigen::Vector2d> points,
                                  Cells& cells, Insertion& sums) const {
  // frame * p, and its cell as CellIndex finds it, to the bit.
  const Pose2& pose = frame.pose();
  const double c = frame.cos(), s = frame.sin();
  const auto stride = static_cast<std::uint32_t>(width_);
  // The cells of a chunk of points first, then the set: in one loop, each point's arithmetic
  // waited on the set's read-modify-write of the point before (measured: a fifth faster apart).
  constexpr std::size_t kChunk = 128;
  std::array<std::uint32_t, kChunk> chunk_cells;
  // Local sums: through the reference, every point would store to memory and reload.
  std::uint64_t inside = 0, fresh = 0;
  // Neighbouring returns near the laser often share a cell, and a repeat of the cell before needs
  // no look-up in the set. That pays for a hash set's look-up (the local search: 15 % less time),
  // not for a bit set's (the global search, which also takes one return in two: 8 % more).
  constexpr bool kSkipRepeats = std::is_same_v<Cells, CellSet>;
  std::uint32_t last = std::numeric_limits<std::uint32_t>::max();  // no cell has this index
  for (std::size_t begin = 0; begin < points.size(); begin += kChunk) {
    const std::size_t end = std::min(points.size(), begin + kChunk);
    std::size_t n = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector2d& p = points[i];
      const double x = (pose.x() + c * p.x() - s * p.y() - origin_.x()) / resolution_;
      const double y = (pose.y() + s * p.x() + c * p.y() - origin_.y()) / resolution_;
      // As in WorldToCell: in the grid exactly when the truncation is the floor; NaN is outside.
      const bool in = x >= 0 && y >= 0 && x < width_ && y < height_;
      // Written whether in or not, kept only when in (and not a repeat): no branch on the point.
      const std::uint32_t cell = static_cast<std::uint32_t>(in ? y : 0.0) * stride +
                                 static_cast<std::uint32_t>(in ? x : 0.0);
      chunk_cells[n] = cell;
      inside += in;
      if constexpr (kSkipRepeats) {
        n += in & (cell != last);
        last = in ? cell : last;
      } else {
        n += in;
      }
    }
    for (std::size_t k = 0; k < n; ++k) {
      // Without a branch on whether the cell is new: that one mispredicts.
      fresh += static_cast<std::uint64_t>(cells.Insert(chunk_cells[k])) &
               static_cast<std::uint64_t>(!occupied(chunk_cells[k]));
    }
  }
  sums.inside += inside;
  sums.fresh += fresh;
}

template void HitCountGrid::CountInsertion(const Pose2Frame&, std::span<const Eigen::Vector2d>,
                                           CellSet&, Insertion&) const;
template void HitCountGrid::CountInsertion(const Pose2Frame&, std::span<const Eigen::Vector2d>,
                                           GridCellSet&, Insertion&) const;

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
