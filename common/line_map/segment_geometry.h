#ifndef EVOSLAM_COMMON_LINE_MAP_SEGMENT_GEOMETRY_H_
#define EVOSLAM_COMMON_LINE_MAP_SEGMENT_GEOMETRY_H_

#include <Eigen/Core>

#include "common/line_map/line_map.h"

namespace evoslam {

// Euclidean distance from point p to the closed segment s (to s.a when s has zero length).
double PointSegmentDistance(const Eigen::Vector2d& p, const Segment& s);

// Smallest distance between two closed segments; 0 when they touch or cross.
double SegmentSegmentDistance(const Segment& s, const Segment& t);

// Smallest distance from segment s to any wall of the map, or `limit` when no wall is closer.
double WallClearance(const LineMap& map, const Segment& s, double limit);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LINE_MAP_SEGMENT_GEOMETRY_H_
