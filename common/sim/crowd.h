#ifndef EVOSLAM_COMMON_SIM_CROWD_H_
#define EVOSLAM_COMMON_SIM_CROWD_H_

#include <Eigen/Core>
#include <span>
#include <vector>

#include "common/line_map/line_map.h"
#include "common/util/random.h"

namespace evoslam {

// Pedestrians, as discs, each walking in a straight line to a random free point of the map
// and then on to another. Walks keep the disc clear of the walls.
class Crowd {
 public:
  // Places `count` pedestrians at random points of the map's bounds where the disc is clear of
  // every wall. Throws Error when no such point turns up.
  Crowd(const LineMap& map, int count, double radius, double speed, Rng& rng);

  // Moves every pedestrian `dt` seconds along its walk, choosing a new destination on arrival
  // (staying put when no reachable one turns up).
  void Advance(const LineMap& map, double dt, Rng& rng);

  // Distance along the ray to the nearest pedestrian, or max_range. A pedestrian whose disc
  // contains the origin is not seen (the robot cannot be inside a person).
  double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const;

  std::span<const Eigen::Vector2d> positions() const { return positions_; }
  double radius() const { return radius_; }

 private:
  bool FreeSpot(const LineMap& map, const Eigen::Vector2d& p) const;
  Eigen::Vector2d RandomPoint(const LineMap& map, Rng& rng) const;

  double radius_;
  double speed_;
  std::vector<Eigen::Vector2d> positions_;
  std::vector<Eigen::Vector2d> targets_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_CROWD_H_
