#include "common/sim/trajectory.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "common/line_map/segment_geometry.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// Turns sharper than this (radians) are made on the spot at the waypoint: an arc tangent to
// two nearly opposite legs would have to start far before the corner.
constexpr double kReversal = Radians(179.0);

// A straight stretch (radius < 0) or an arc; an arc of radius 0 is a turn on the spot.
struct Piece {
  Eigen::Vector2d start;  // lines: first point; arcs: centre
  double heading = 0.0;   // at the start
  double length = 0.0;    // lines only
  double sweep = 0.0;     // arcs only: signed heading change
  double radius = -1.0;
  double sampled_length = 0.0;  // length in the sampling parameter

  Pose2 At(double fraction) const {
    if (radius < 0.0) {
      const Eigen::Vector2d u(std::cos(heading), std::sin(heading));
      return Pose2(start + fraction * length * u, heading);
    }
    const double h = heading + fraction * sweep;
    const double side = sweep < 0.0 ? -1.0 : 1.0;
    return Pose2(start + side * radius * Eigen::Vector2d(std::sin(h), -std::cos(h)), h);
  }
};

// The route's distinct waypoints and the straight legs between them.
struct Legs {
  std::vector<Eigen::Vector2d> points;
  std::vector<Eigen::Vector2d> direction;
  std::vector<double> length;
  std::vector<double> heading;

  std::size_t size() const { return length.size(); }
};

Legs MakeLegs(std::span<const Eigen::Vector2d> waypoints, const PathOptions& options) {
  if (!IsFinitePositive(options.step) || !IsFiniteNonNegative(options.turn_radius) ||
      !IsFinitePositive(options.min_turn_sampling_radius)) {
    throw Error("path: step and sampling radius must be positive, turn radius non-negative");
  }
  Legs legs;
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    if (!waypoints[i].allFinite()) {
      throw Error("path: waypoint " + std::to_string(i) + " is not finite");
    }
    if (legs.points.empty() || (waypoints[i] - legs.points.back()).norm() > 1e-9) {
      legs.points.push_back(waypoints[i]);
    }
  }
  if (legs.points.size() < 2) throw Error("path: a route needs at least two distinct waypoints");
  for (std::size_t i = 0; i + 1 < legs.points.size(); ++i) {
    const Eigen::Vector2d d = legs.points[i + 1] - legs.points[i];
    legs.length.push_back(d.norm());
    legs.direction.push_back(d / legs.length.back());
    legs.heading.push_back(std::atan2(d.y(), d.x()));
  }
  return legs;
}

// The arc that rounds corner i (joining leg i - 1 to leg i) with at most max_radius: tangent
// to both legs, from `cut` before the waypoint to `cut` after it. Inner legs give each of
// their corners at most half their length; a reversal becomes a turn on the spot.
Piece Corner(const Legs& legs, std::size_t i, double max_radius, double min_sampling_radius) {
  const double turn = WrapAngle(legs.heading[i] - legs.heading[i - 1]);
  const double half = 0.5 * std::abs(turn);
  double cut = 0.0;
  double radius = 0.0;
  if (half > 0.0 && 2.0 * half <= kReversal) {
    const double room_in = i == 1 ? legs.length[0] : 0.5 * legs.length[i - 1];
    const double room_out = i + 1 == legs.size() ? legs.length[i] : 0.5 * legs.length[i];
    cut = std::min({max_radius * std::tan(half), room_in, room_out});
    radius = cut / std::tan(half);
  }
  const double side = turn < 0.0 ? -1.0 : 1.0;
  const Eigen::Vector2d& u = legs.direction[i - 1];
  const Eigen::Vector2d start = legs.points[i] - cut * u;
  const Eigen::Vector2d centre = start + side * radius * Eigen::Vector2d(-u.y(), u.x());
  return {centre, legs.heading[i - 1],
          0.0,    turn,
          radius, std::abs(turn) * std::max(radius, min_sampling_radius)};
}

// Where the arc of a corner leaves the waypoint's outgoing leg, and enters the incoming one.
double CornerCut(const Piece& corner) {
  return corner.sweep == 0.0 ? 0.0 : corner.radius * std::tan(0.5 * std::abs(corner.sweep));
}

std::vector<Pose2> Sample(const Legs& legs, std::span<const Piece> corners, double step) {
  // corners[i] rounds waypoint i; the first and last waypoints have none (sweep 0).
  std::vector<Piece> pieces;
  Eigen::Vector2d at = legs.points.front();
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const Eigen::Vector2d leg_end =
        legs.points[i + 1] - CornerCut(corners[i + 1]) * legs.direction[i];
    const double straight = (leg_end - at).norm();
    if (straight > 0.0) pieces.push_back({at, legs.heading[i], straight, 0.0, -1.0, straight});
    if (i + 1 == legs.size()) break;
    if (corners[i + 1].sweep != 0.0) pieces.push_back(corners[i + 1]);
    at = legs.points[i + 1] + CornerCut(corners[i + 1]) * legs.direction[i + 1];
  }

  double total = 0.0;
  for (const Piece& p : pieces) total += p.sampled_length;
  const auto count = static_cast<std::size_t>(std::max(1.0, std::round(total / step)));
  std::vector<Pose2> path;
  path.reserve(count + 1);
  std::size_t piece = 0;
  double piece_start = 0.0;
  for (std::size_t k = 0; k <= count; ++k) {
    const double s = total * static_cast<double>(k) / static_cast<double>(count);
    while (piece + 1 < pieces.size() && s > piece_start + pieces[piece].sampled_length) {
      piece_start += pieces[piece].sampled_length;
      ++piece;
    }
    const Piece& p = pieces[piece];
    const double fraction = std::clamp((s - piece_start) / p.sampled_length, 0.0, 1.0);
    path.push_back(p.At(fraction));
  }
  return path;
}

}  // namespace

std::vector<Pose2> SmoothPath(std::span<const Eigen::Vector2d> waypoints,
                              const PathOptions& options) {
  const Legs legs = MakeLegs(waypoints, options);
  std::vector<Piece> corners(legs.points.size());
  for (std::size_t i = 1; i < legs.size(); ++i) {
    corners[i] = Corner(legs, i, options.turn_radius, options.min_turn_sampling_radius);
  }
  return Sample(legs, corners, options.step);
}

PathClearance MeasureClearance(const LineMap& map, std::span<const Pose2> path, double limit) {
  PathClearance result{limit, 0};
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector2d a = path[i].translation();
    const Eigen::Vector2d b = i + 1 < path.size() ? path[i + 1].translation() : a;
    const double d = WallClearance(map, {a, b}, limit);
    if (d < result.distance) result = {d, i};
  }
  return result;
}

double PathLength(std::span<const Pose2> path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    length += (path[i].translation() - path[i - 1].translation()).norm();
  }
  return length;
}

std::vector<Pose2> RouteTrajectory(const World& world, double step) {
  // Arcs no wider than the clearance keep it wherever both legs of their corner do (any point
  // that far from both legs lies beyond the arc's centre), so only the legs can bring the path
  // too close to a wall.
  static_assert(PathOptions{}.turn_radius <= kMinWallClearance);
  std::vector<Pose2> path;
  try {
    path = SmoothPath(world.waypoints, {.step = step});
  } catch (const Error& e) {
    throw Error("world \"" + world.name + "\": " + e.what());
  }
  const PathClearance clearance = MeasureClearance(world.map, path, kMinWallClearance);
  if (clearance.distance < kMinWallClearance) {
    const Pose2& p = path[clearance.pose];
    throw Error(fmt::format(
        "world \"{}\": the route comes {:.3f} m from a wall near ({:.2f}, {:.2f}) (pose {}); it "
        "must keep {} m",
        world.name, clearance.distance, p.x(), p.y(), clearance.pose, kMinWallClearance));
  }
  return path;
}

}  // namespace evoslam
