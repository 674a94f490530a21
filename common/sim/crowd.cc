#include "common/sim/crowd.h"

#include <cmath>

#include "common/line_map/segment_geometry.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr double kWallMargin = 0.05;  // metres between a disc and the walls
constexpr int kPlacementTries = 10000;
constexpr int kDestinationTries = 50;

}  // namespace

Crowd::Crowd(const LineMap& map, int count, double radius, double speed, Rng& rng)
    : radius_(radius), speed_(speed) {
  for (int i = 0; i < count; ++i) {
    Eigen::Vector2d p;
    int tries = 0;
    do {
      if (++tries > kPlacementTries) {
        throw Error("cannot place pedestrians: no free spot for a disc of radius " +
                    std::to_string(radius) + " m found in the map");
      }
      p = RandomPoint(map, rng);
    } while (!FreeSpot(map, p));
    positions_.push_back(p);
    targets_.push_back(p);
  }
}

bool Crowd::FreeSpot(const LineMap& map, const Eigen::Vector2d& p) const {
  return map.SegmentsNear(p, radius_ + kWallMargin).empty();
}

Eigen::Vector2d Crowd::RandomPoint(const LineMap& map, Rng& rng) const {
  const Bounds& b = map.bounds();
  const double x = rng.Uniform(b.min.x(), b.max.x());
  return {x, rng.Uniform(b.min.y(), b.max.y())};
}

void Crowd::Advance(const LineMap& map, double dt, Rng& rng) {
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    const double left = speed_ * dt;
    const Eigen::Vector2d to_target = targets_[i] - positions_[i];
    const double distance = to_target.norm();
    if (distance > left) {
      positions_[i] += to_target * (left / distance);
      continue;
    }
    positions_[i] = targets_[i];
    for (int k = 0; k < kDestinationTries; ++k) {
      const Eigen::Vector2d p = RandomPoint(map, rng);
      if (WallClearance(map, {positions_[i], p}, radius_ + kWallMargin) >= radius_ + kWallMargin) {
        targets_[i] = p;
        break;
      }
    }
  }
}

double Crowd::CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const {
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  const double r2 = radius_ * radius_;
  double best = max_range;
  for (const Eigen::Vector2d& c : positions_) {
    // |origin + t d - c| = radius: t^2 + 2 b t + q = 0 with b = m.d and q = |m|^2 - radius^2.
    const Eigen::Vector2d m = origin - c;
    const double q = m.squaredNorm() - r2;
    if (q <= 0.0) continue;
    const double b = m.dot(d);
    const double disc = b * b - q;
    if (b >= 0.0 || disc < 0.0) continue;  // pointing away or passing by
    const double t = -b - std::sqrt(disc);
    if (t < best) best = t;
  }
  return best;
}

}  // namespace evoslam
