#include "common/slam/immune/key_points.h"

#include <algorithm>
#include <cmath>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <ranges>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "common/slam/immune/scan_gaps.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// A cell of the key point grid: the world square [x, x + 1) * cell_size by [y, y + 1) * cell_size.
struct KeyCell {
  std::int32_t x = 0;
  std::int32_t y = 0;
  auto operator<=>(const KeyCell&) const = default;
};

Eigen::Vector2d KeyCellCentre(const KeyCell& cell, double cell_size) {
  return cell_size * Eigen::Vector2d(cell.x + 0.5, cell.y + 0.5);
}

// Beyond this many cells from the origin a sighting is dropped: its pose is garbage, and the cell
// would overflow.
constexpr double kMaxKeyCellIndex = 1 << 30;

// A sighting placed in the world by its scan's pose.
struct PlacedKeySighting {
  KeyPointSighting sighting;
  Eigen::Vector2d world;
  Eigen::Vector2d viewpoint;
  KeyCell cell;
};

std::vector<PlacedKeySighting> PlaceKeyPointSightings(const Dataset& dataset,
                                                      std::span<const Pose2> laser_poses,
                                                      const proto::KeyPointParams& params,
                                                      double max_range_m) {
  std::vector<PlacedKeySighting> placed;
  for (std::size_t s = 0; s < laser_poses.size(); ++s) {
    const Pose2& pose = laser_poses[s];
    for (const ScanGap& gap : FindScanGaps(dataset.scans[s], params, max_range_m)) {
      const Eigen::Vector2d world = pose * gap.point;
      const Eigen::Vector2d cell = (world / params.cell_size_m()).array().floor();
      if (!(cell.cwiseAbs().maxCoeff() < kMaxKeyCellIndex)) continue;
      placed.push_back(
          {{s, gap.beam, gap.point},
           world,
           pose.translation(),
           {static_cast<std::int32_t>(cell.x()), static_cast<std::int32_t>(cell.y())}});
    }
  }
  return placed;
}

// A cell with what it gathers from the cells around it.
struct KeyCandidate {
  KeyCell cell;
  std::size_t independent = 0;        // sightings from distinct viewpoints
  std::size_t own = 0;                // sightings in the cell itself
  double centre_offset = 0.0;         // from the cell's centre to the mean of its sightings, m
  std::vector<std::size_t> gathered;  // indices into the placed sightings, ascending

  // Ordered strongest first; the cell breaks the last ties so that the order is total.
  auto Strength() const {
    return std::make_tuple(independent, gathered.size(), own, -centre_offset);
  }
  bool StrongerThan(const KeyCandidate& other) const {
    const auto a = Strength();
    const auto b = other.Strength();
    return a != b ? a > b : cell < other.cell;
  }
};

// Dempster's rule for n simple support functions of mass m on the same proposition.
double KeyPointBelief(std::size_t n, double m) {
  return 1.0 - std::pow(1.0 - m, static_cast<double>(n));
}

std::size_t CountIndependentSightings(std::span<const PlacedKeySighting> placed,
                                      std::span<const std::size_t> gathered, double min_shift) {
  std::vector<Eigen::Vector2d> counted;
  for (const std::size_t i : gathered) {
    const Eigen::Vector2d& v = placed[i].viewpoint;
    const bool fresh = std::ranges::all_of(
        counted, [&](const Eigen::Vector2d& c) { return (c - v).norm() >= min_shift; });
    if (fresh) counted.push_back(v);
  }
  return counted.size();
}

// Every cell holding a sighting, with what it gathers, when its belief reaches confirm_belief.
std::vector<KeyCandidate> ConfirmedKeyCandidates(std::span<const PlacedKeySighting> placed,
                                                 const proto::KeyPointParams& params) {
  // The sightings sorted by cell (then by index), so that one column of a cell's neighbourhood
  // is one run.
  std::vector<std::size_t> by_cell(placed.size());
  for (std::size_t i = 0; i < placed.size(); ++i) by_cell[i] = i;
  std::ranges::sort(by_cell, [&](std::size_t a, std::size_t b) {
    return std::tie(placed[a].cell, a) < std::tie(placed[b].cell, b);
  });
  const auto column = [&](KeyCell low, KeyCell high) {
    const auto first =
        std::ranges::lower_bound(by_cell, low, {}, [&](std::size_t i) { return placed[i].cell; });
    const auto last = std::ranges::upper_bound(first, by_cell.end(), high, {},
                                               [&](std::size_t i) { return placed[i].cell; });
    return std::ranges::subrange(first, last);
  };

  std::vector<KeyCandidate> confirmed;
  for (std::size_t k = 0; k < by_cell.size();) {
    KeyCandidate c;
    c.cell = placed[by_cell[k]].cell;
    for (std::int32_t dx = -1; dx <= 1; ++dx) {
      for (const std::size_t i :
           column({c.cell.x + dx, c.cell.y - 1}, {c.cell.x + dx, c.cell.y + 1})) {
        c.gathered.push_back(i);
        c.own += placed[i].cell == c.cell;
      }
    }
    k += c.own;
    std::ranges::sort(c.gathered);
    c.independent = CountIndependentSightings(placed, c.gathered, params.min_view_shift_m());
    if (KeyPointBelief(c.independent, params.sighting_belief()) < params.confirm_belief()) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const std::size_t i : c.gathered) mean += placed[i].world;
    mean /= static_cast<double>(c.gathered.size());
    c.centre_offset = (mean - KeyCellCentre(c.cell, params.cell_size_m())).norm();
    confirmed.push_back(std::move(c));
  }
  return confirmed;
}

// The strongest candidates, none within two cells of a stronger one: closer, their gathered
// sightings would overlap.
std::vector<KeyCandidate> StrongestKeyCandidates(std::vector<KeyCandidate> candidates) {
  std::ranges::sort(candidates,
                    [](const KeyCandidate& a, const KeyCandidate& b) { return a.StrongerThan(b); });
  std::set<KeyCell> taken;
  std::vector<KeyCandidate> kept;
  for (KeyCandidate& c : candidates) {
    const bool near_stronger = [&] {
      for (std::int32_t dx = -2; dx <= 2; ++dx) {
        for (std::int32_t dy = -2; dy <= 2; ++dy) {
          if (taken.contains({c.cell.x + dx, c.cell.y + dy})) return true;
        }
      }
      return false;
    }();
    if (near_stronger) continue;
    taken.insert(c.cell);
    kept.push_back(std::move(c));
  }
  return kept;
}

}  // namespace

void ValidateKeyPointParams(const proto::KeyPointParams& p) {
  if (!IsFinitePositive(p.section_ratio()))
    throw Error("key_points.section_ratio: must be positive and finite");
  if (p.min_section_points() == 0) throw Error("key_points.min_section_points: must be >= 1");
  if (!IsFiniteNonNegative(p.min_gap_m()))
    throw Error("key_points.min_gap_m: must be finite and not negative");
  if (!IsFinitePositive(p.cell_size_m()))
    throw Error("key_points.cell_size_m: must be positive and finite");
  if (!(p.sighting_belief() > 0.0 && p.sighting_belief() < 1.0))
    throw Error("key_points.sighting_belief: must be in (0, 1)");
  if (!(p.confirm_belief() > 0.0 && p.confirm_belief() < 1.0))
    throw Error("key_points.confirm_belief: must be in (0, 1)");
  if (!IsFiniteNonNegative(p.min_view_shift_m()))
    throw Error("key_points.min_view_shift_m: must be finite and not negative");
}

std::vector<KeyPoint> FindKeyPoints(const Dataset& dataset, std::span<const Pose2> laser_poses,
                                    const proto::KeyPointParams& params, double max_range_m) {
  ValidateKeyPointParams(params);
  if (!IsFinitePositive(max_range_m)) {
    throw Error("key points: the maximum range must be positive and finite, not " +
                std::to_string(max_range_m));
  }
  if (laser_poses.size() > dataset.scans.size()) {
    throw Error("key points: " + std::to_string(laser_poses.size()) + " poses for " +
                std::to_string(dataset.scans.size()) + " scans");
  }
  const std::vector<PlacedKeySighting> placed =
      PlaceKeyPointSightings(dataset, laser_poses, params, max_range_m);
  std::vector<KeyCandidate> kept = StrongestKeyCandidates(ConfirmedKeyCandidates(placed, params));
  // Kept candidates gather disjoint sightings, so their first ones order them strictly.
  std::ranges::sort(kept, {}, [](const KeyCandidate& c) { return c.gathered.front(); });

  std::vector<KeyPoint> key_points;
  key_points.reserve(kept.size());
  for (const KeyCandidate& c : kept) {
    KeyPoint& k = key_points.emplace_back();
    k.position = KeyCellCentre(c.cell, params.cell_size_m());
    k.belief = KeyPointBelief(c.independent, params.sighting_belief());
    k.sightings.reserve(c.gathered.size());
    for (const std::size_t i : c.gathered) k.sightings.push_back(placed[i].sighting);
  }
  return key_points;
}

}  // namespace evoslam
