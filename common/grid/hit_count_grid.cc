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

namespace {

// A cell's count moved by `delta`, never below zero: hits and ray crossings alike.
std::uint32_t Moved(std::uint32_t count, int delta) {
  if (delta >= 0) return count + static_cast<std::uint32_t>(delta);
  return count - std::min(count, static_cast<std::uint32_t>(-static_cast<long long>(delta)));
}

}  // namespace

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
    : geometry_(resolution, origin, width, height) {
  if (static_cast<long long>(width) * height > kMaxCells) {
    throw Error("hit count grid: " + std::to_string(width) + " x " + std::to_string(height) +
                " cells is over the limit of " + std::to_string(kMaxCells));
  }
  counts_ = TiledCounts(width, height);
  occupied_bits_.assign((geometry_.cell_count() + 63) / 64, 0);
}

std::uint32_t HitCountGrid::count(int x, int y) const {
  if (!geometry_.Contains(x, y)) {
    throw std::out_of_range("hit count grid: cell (" + std::to_string(x) + ", " +
                            std::to_string(y) + ") is outside the grid");
  }
  return counts_.get(x, y);
}

std::uint32_t HitCountGrid::count(std::size_t index) const {
  if (index >= geometry_.cell_count()) {
    throw std::out_of_range("hit count grid: cell " + std::to_string(index) +
                            " is outside the grid");
  }
  const auto w = static_cast<std::size_t>(width());
  return counts_.get(static_cast<int>(index % w), static_cast<int>(index / w));
}

bool HitCountGrid::Add(const Eigen::Vector2d& point, int delta) {
  const auto cell = WorldToCell(point);
  if (!cell) return false;
  const std::uint32_t before = counts_.get(cell->x(), cell->y());
  const std::uint32_t c = Moved(before, delta);
  counts_.set(cell->x(), cell->y(), c);
  total_ = total_ - before + c;
  occupied_ = occupied_ - (before > 0) + (c > 0);
  if ((before > 0) != (c > 0)) {
    const std::size_t index = geometry_.Index(cell->x(), cell->y());
    occupied_bits_[index / 64] ^= std::uint64_t{1} << (index % 64);
  }
  return true;
}

std::size_t HitCountGrid::AddScan(const LaserScan& scan, const Pose2& pose, int delta) {
  std::size_t outside = 0;
  const Pose2Frame frame(pose);
  for (const Eigen::Vector2d& p : ReturnPoints(scan)) outside += !Add(frame * p, delta);
  if (tracks_rays() && delta != 0) {
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const double r = scan.ranges[i];
      // A return's ray ends at it; a beam that returned nothing crossed free space to the range.
      const double reach = scan.is_return(i) ? r : (r >= scan.range_max ? scan.range_max : 0.0);
      if (!(reach > 0.0)) continue;
      const double a = scan.angle(i);
      AddCrossings(pose.translation(),
                   frame * Eigen::Vector2d(reach * std::cos(a), reach * std::sin(a)), delta);
    }
  }
  return outside;
}

void HitCountGrid::TrackRays() {
  crossings_ = TiledCounts(width(), height());
  crossed_bits_.assign(occupied_bits_.size(), 0);
}

void HitCountGrid::AddCrossings(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int delta) {
  // Amanatides and Woo's traversal: from cell to cell across the nearer boundary.
  const Eigen::Vector2d a = geometry_.ToCells(from), b = geometry_.ToCells(to);
  if (!geometry_.ContainsCells(a.x(), a.y()) || !b.allFinite()) return;
  int x = static_cast<int>(a.x()), y = static_cast<int>(a.y());
  const int end_x = static_cast<int>(std::floor(b.x())),
            end_y = static_cast<int>(std::floor(b.y()));
  const Eigen::Vector2d d = b - a;
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  const double delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kNever;
  const double delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kNever;
  double next_x = d.x() != 0.0 ? ((d.x() > 0 ? x + 1 - a.x() : a.x() - x) * delta_x) : kNever;
  double next_y = d.y() != 0.0 ? ((d.y() > 0 ? y + 1 - a.y() : a.y() - y) * delta_y) : kNever;
  while (x != end_x || y != end_y) {
    const std::uint32_t before = crossings_.get(x, y);
    const std::uint32_t c = Moved(before, delta);
    crossings_.set(x, y, c);
    if ((before > 0) != (c > 0)) {
      const std::size_t i = geometry_.Index(x, y);
      crossed_bits_[i / 64] ^= std::uint64_t{1} << (i % 64);
    }
    if (next_x < next_y) {
      if (next_x > 1.0) break;
      x += step_x;
      next_x += delta_x;
    } else {
      if (next_y > 1.0) break;
      y += step_y;
      next_y += delta_y;
    }
    if (!geometry_.Contains(x, y)) break;
  }
}

bool HitCountGrid::Frontier(std::size_t index) const {
  if (crossed_bits_.empty() || crossed(index) || occupied(index)) return false;
  const auto w = static_cast<std::size_t>(width());
  const std::size_t x = index % w, y = index / w;
  if (x == 0 || y == 0 || x + 1 >= w || y + 1 >= static_cast<std::size_t>(height())) return false;
  for (const std::size_t n : {index - w - 1, index - w, index - w + 1, index - 1, index + 1,
                              index + w - 1, index + w, index + w + 1}) {
    if (crossed(n) && !occupied(n)) return true;
  }
  return false;
}

template <typename Cells>
void HitCountGrid::CountInsertion(const Pose2Frame& frame, std::span<const Eigen::Vector2d> points,
                                  Cells& cells, Insertion& sums, bool frontier_free) const {
  // frame * p, and its cell as CellIndex finds it, to the bit.
  const Pose2& pose = frame.pose();
  const double c = frame.cos(), s = frame.sin();
  const auto stride = static_cast<std::uint32_t>(width());
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
      const double x = geometry_.CellX(pose.x() + c * p.x() - s * p.y());
      const double y = geometry_.CellY(pose.y() + s * p.x() + c * p.y());
      // As in WorldToCell: in the grid exactly when the truncation is the floor; NaN is outside.
      const bool in = geometry_.ContainsCells(x, y);
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
    if (frontier_free) {
      for (std::size_t k = 0; k < n; ++k) {
        const bool added = cells.Insert(chunk_cells[k]) && !occupied(chunk_cells[k]);
        fresh += static_cast<std::uint64_t>(added && !Frontier(chunk_cells[k]));
      }
      continue;
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
                                           CellSet&, Insertion&, bool) const;
template void HitCountGrid::CountInsertion(const Pose2Frame&, std::span<const Eigen::Vector2d>,
                                           GridCellSet&, Insertion&, bool) const;

double HitCountGrid::MeanPerOccupied() const {
  return occupied_ > 0 ? static_cast<double>(total_) / static_cast<double>(occupied_) : 0.0;
}

HitCountGrid::WindowSums HitCountGrid::Window(int x0, int y0, int x1, int y1) const {
  const TiledCounts::Sums sums = counts_.Window(std::max(x0, 0), std::max(y0, 0),
                                                std::min(x1, width()), std::min(y1, height()));
  return {.total = sums.total, .occupied = sums.nonzero};
}

std::size_t HitCountGrid::bytes() const {
  return counts_.bytes() + crossings_.bytes() +
         (occupied_bits_.capacity() + crossed_bits_.capacity()) * sizeof(std::uint64_t);
}

}  // namespace evoslam
