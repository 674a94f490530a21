#ifndef EVOSLAM_COMMON_SLAM_SLAM_TESTING_H_
#define EVOSLAM_COMMON_SLAM_SLAM_TESTING_H_

// Helpers shared by the search problems' tests (header-only; test binaries include it).

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "common/grid/hit_count_grid.h"

namespace evoslam::testing {

// What inserting world points into a map adds, counted the plain way the problems must match to
// the bit: every point's cell gathered, then sorted and made unique.
struct CountedInsertion {
  std::vector<std::size_t> cells;  // the cells hit, sorted, each once
  std::size_t inside = 0;          // the points that fall in the map
  std::size_t fresh = 0;           // the cells they make occupied
};

inline CountedInsertion CountAsWritten(const HitCountGrid& map,
                                       std::span<const Eigen::Vector2d> world_points) {
  CountedInsertion r;
  for (const Eigen::Vector2d& p : world_points) {
    if (const auto c = map.CellIndex(p)) r.cells.push_back(*c);
  }
  r.inside = r.cells.size();
  std::sort(r.cells.begin(), r.cells.end());
  r.cells.erase(std::unique(r.cells.begin(), r.cells.end()), r.cells.end());
  for (const std::size_t c : r.cells) r.fresh += map.count(c) == 0;
  return r;
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_SLAM_SLAM_TESTING_H_
