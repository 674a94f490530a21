#include "common/line_map/segment_geometry.h"

#include <algorithm>
#include <cmath>

namespace evoslam {
namespace {

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// Orientation of c relative to the directed line a->b: +1 left, -1 right, 0 on it.
int Side(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double cross = Cross(b - a, c - a);
  return (cross > 0.0) - (cross < 0.0);
}

bool ProperlyCross(const Segment& s, const Segment& t) {
  const int s1 = Side(s.a, s.b, t.a);
  const int s2 = Side(s.a, s.b, t.b);
  const int t1 = Side(t.a, t.b, s.a);
  const int t2 = Side(t.a, t.b, s.b);
  return s1 * s2 < 0 && t1 * t2 < 0;
}

}  // namespace

double PointSegmentDistance(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d e = s.b - s.a;
  const double length_sq = e.squaredNorm();
  if (length_sq == 0.0) return (p - s.a).norm();
  const double u = std::clamp((p - s.a).dot(e) / length_sq, 0.0, 1.0);
  return (p - (s.a + u * e)).norm();
}

double SegmentSegmentDistance(const Segment& s, const Segment& t) {
  if (ProperlyCross(s, t)) return 0.0;
  // Without a proper crossing the closest pair includes an endpoint of one of the segments
  // (touching and collinear overlaps give 0 here too).
  return std::min({PointSegmentDistance(s.a, t), PointSegmentDistance(s.b, t),
                   PointSegmentDistance(t.a, s), PointSegmentDistance(t.b, s)});
}

double WallClearance(const LineMap& map, const Segment& s, double limit) {
  double clearance = limit;
  const Eigen::Vector2d middle = 0.5 * (s.a + s.b);
  for (const std::size_t i : map.SegmentsNear(middle, 0.5 * (s.b - s.a).norm() + limit)) {
    clearance = std::min(clearance, SegmentSegmentDistance(s, map.segments()[i]));
  }
  return clearance;
}

}  // namespace evoslam
