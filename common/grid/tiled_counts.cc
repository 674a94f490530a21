#include "common/grid/tiled_counts.h"

#include <algorithm>

namespace evoslam {

TiledCounts::TiledCounts(int width, int height)
    : tiles_x_(static_cast<std::size_t>((width + kTileSide - 1) >> kTileShift)),
      tiles_(tiles_x_ * static_cast<std::size_t>((height + kTileSide - 1) >> kTileShift)) {}

TiledCounts::Sums TiledCounts::Window(int x0, int y0, int x1, int y1) const {
  Sums sums;
  // Tile by tile, so that the many tiles of a window never touched cost a look each.
  for (int ty = y0 >> kTileShift; y0 < y1 && ty <= (y1 - 1) >> kTileShift; ++ty) {
    const int cy0 = std::max(y0, ty << kTileShift), cy1 = std::min(y1, (ty + 1) << kTileShift);
    for (int tx = x0 >> kTileShift; x0 < x1 && tx <= (x1 - 1) >> kTileShift; ++tx) {
      const std::vector<std::uint32_t>& tile = tiles_[TileOf(tx << kTileShift, ty << kTileShift)];
      if (tile.empty()) continue;
      const int cx0 = std::max(x0, tx << kTileShift), cx1 = std::min(x1, (tx + 1) << kTileShift);
      for (int y = cy0; y < cy1; ++y) {
        for (int x = cx0; x < cx1; ++x) {
          const std::uint32_t c = tile[InTile(x, y)];
          sums.total += c;
          sums.nonzero += c > 0;
        }
      }
    }
  }
  return sums;
}

std::size_t TiledCounts::tiles_allocated() const {
  return static_cast<std::size_t>(
      std::count_if(tiles_.begin(), tiles_.end(),
                    [](const std::vector<std::uint32_t>& t) { return !t.empty(); }));
}

std::size_t TiledCounts::bytes() const {
  std::size_t bytes = tiles_.capacity() * sizeof(std::vector<std::uint32_t>);
  for (const std::vector<std::uint32_t>& tile : tiles_) {
    bytes += tile.capacity() * sizeof(std::uint32_t);
  }
  return bytes;
}

}  // namespace evoslam
