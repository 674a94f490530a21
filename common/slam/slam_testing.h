#ifndef EVOSLAM_COMMON_SLAM_SLAM_TESTING_H_
#define EVOSLAM_COMMON_SLAM_SLAM_TESTING_H_

// Helpers shared by the search problems' tests (header-only; test binaries include it).

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "common/grid/hit_count_grid.h"
#include "common/sensor/dataset.h"
#include "common/slam/rss/rss_slam.h"

namespace evoslam::testing {

// RunRssSlam with the method's parameters `rss` and `seed`, every other parameter at its default.
inline RssSlamResult RunRss(const Dataset& dataset, const RssSlamParams& rss, std::uint64_t seed,
                            const RssSlamRuntime& runtime = {}) {
  proto::SlamParams params;
  *params.mutable_rss() = rss;
  params.set_seed(seed);
  return RunRssSlam(dataset, params, runtime);
}

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

// The first place a simulated drive comes back to: (earlier, later) scans whose true poses lie
// within `radius` of each other, at least `min_gap` scans apart, `later` as small as can be.
inline std::optional<std::pair<std::size_t, std::size_t>> FirstRevisit(const Dataset& drive,
                                                                       std::size_t min_gap,
                                                                       double radius) {
  const auto& scans = drive.scans;
  for (std::size_t j = min_gap; j < scans.size(); ++j) {
    for (std::size_t i = 0; i + min_gap <= j; ++i) {
      if ((scans[i].true_pose->translation() - scans[j].true_pose->translation()).norm() < radius) {
        return std::pair{i, j};
      }
    }
  }
  return std::nullopt;
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_SLAM_SLAM_TESTING_H_
