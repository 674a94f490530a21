#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_TESTING_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_TESTING_H_

// Helpers shared by the evidence grid's tests (header-only; test binaries include it).

#include <cstddef>
#include <vector>

#include "common/sensor/dataset.h"
#include "common/sim/sim_testing.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/immune/evidence_grid.h"
#include "common/util/random.h"

namespace evoslam::testing {

// A 5 cm grid over a room from the origin and `margin` metres around it, its cells offset half a
// cell so that the walls of Room() run through the middle of cells, not along their edges.
inline GridGeometry EvidenceRoomGeometry(double width, double height, double margin = 1.0) {
  const double res = 0.05;
  const Eigen::Vector2d origin(-margin - 0.5 * res, -margin - 0.5 * res);
  return GridGeometry(res, origin, static_cast<int>((width + 2 * margin) / res) + 1,
                      static_cast<int>((height + 2 * margin) / res) + 1);
}

// Noise-free scans of a 6 x 4 m Room, one every `step` metres of the loop the simulator drives.
inline Dataset SimulatedRoomScans(double step = 0.4) {
  SimulationOptions options;
  options.step = step;
  return Simulate(WorldFromLineMap(Room(6.0, 4.0), "room"), options);
}

// The scans prepared and placed at their true poses.
struct PreparedScans {
  std::vector<EvidenceScan> scans;
  std::vector<PlacedScan> placed;

  PreparedScans(const Dataset& log, const proto::EvidenceGridParams& params) {
    scans.reserve(log.scans.size());
    for (const LaserScan& s : log.scans) scans.emplace_back(s, params);
    for (std::size_t i = 0; i < scans.size(); ++i) {
      placed.push_back({&scans[i], *log.scans[i].true_pose});
    }
  }
};

// The same placements, each pose moved by up to `shift` metres on each axis and `turn` radians.
inline std::vector<PlacedScan> Perturbed(std::vector<PlacedScan> placed, double shift, double turn,
                                         std::uint64_t seed) {
  Rng rng(seed);
  for (PlacedScan& p : placed) {
    p.pose = Pose2(p.pose.x() + rng.Uniform(-shift, shift), p.pose.y() + rng.Uniform(-shift, shift),
                   p.pose.theta() + rng.Uniform(-turn, turn));
  }
  return placed;
}

// Every cell's two sums, to compare whole grids.
inline std::vector<std::uint32_t> AllUnits(const EvidenceGrid& grid) {
  std::vector<std::uint32_t> units;
  units.reserve(2 * grid.geometry().cell_count());
  for (std::size_t c = 0; c < grid.geometry().cell_count(); ++c) {
    units.push_back(grid.occupied_units(c));
    units.push_back(grid.empty_units(c));
  }
  return units;
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_TESTING_H_
