#ifndef EVOSLAM_COMMON_GRID_TILED_COUNTS_H_
#define EVOSLAM_COMMON_GRID_TILED_COUNTS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace evoslam {

// A count per cell of a width x height grid, all zero at first, kept in square tiles of
// kTileSide x kTileSide cells, each allocated when one of its counts first rises above zero. A
// SLAM map must cover wherever a search could put a return (the odometry's whole drifted path and
// the laser's reach around it) while its scans fall in a small part of that: the tiles hold
// memory for that part alone.
class TiledCounts {
 public:
  static constexpr int kTileShift = 6;
  static constexpr int kTileSide = 1 << kTileShift;  // cells
  static constexpr std::size_t kTileCells = std::size_t{kTileSide} * kTileSide;

  // No cells.
  TiledCounts() = default;
  // All zero; width and height must be positive.
  TiledCounts(int width, int height);

  // The count of cell (x, y), which must lie in the grid.
  std::uint32_t get(int x, int y) const {
    const std::vector<std::uint32_t>& tile = tiles_[TileOf(x, y)];
    return tile.empty() ? 0 : tile[InTile(x, y)];
  }
  // Sets the count of cell (x, y), which must lie in the grid; its tile is allocated only when
  // the count is not zero.
  void set(int x, int y, std::uint32_t count) {
    std::vector<std::uint32_t>& tile = tiles_[TileOf(x, y)];
    if (tile.empty()) {
      if (count == 0) return;
      tile.assign(kTileCells, 0);
    }
    tile[InTile(x, y)] = count;
  }

  // The sum of the counts over cells [x0, x1) x [y0, y1), which must lie in the grid, and how
  // many of them are above zero.
  struct Sums {
    std::uint64_t total = 0;
    std::uint64_t nonzero = 0;
  };
  Sums Window(int x0, int y0, int x1, int y1) const;

  std::size_t tiles_allocated() const;
  // The memory kept: the tiles allocated and the table of tiles.
  std::size_t bytes() const;

 private:
  std::size_t TileOf(int x, int y) const {
    return static_cast<std::size_t>(y >> kTileShift) * tiles_x_ +
           static_cast<std::size_t>(x >> kTileShift);
  }
  static std::size_t InTile(int x, int y) {
    return (static_cast<std::size_t>(y & (kTileSide - 1)) << kTileShift) |
           static_cast<std::size_t>(x & (kTileSide - 1));
  }

  std::size_t tiles_x_ = 0;
  // Row by row from the lowest y, kTileCells counts each (row by row), or none while all zero.
  std::vector<std::vector<std::uint32_t>> tiles_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_TILED_COUNTS_H_
