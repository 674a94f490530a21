#include "common/sensor/laser_scan.h"

#include <cmath>

namespace evoslam {

double LaserScan::field_of_view() const {
  return ranges.empty() ? 0.0 : static_cast<double>(ranges.size() - 1) * angle_increment;
}

bool LaserScan::is_return(std::size_t i) const {
  const float r = ranges[i];
  return std::isfinite(r) && r > range_min && r < range_max;
}

std::vector<Eigen::Vector2d> ReturnPoints(const LaserScan& scan) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan.is_return(i)) continue;
    const double a = scan.angle(i), r = scan.ranges[i];
    points.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return points;
}

}  // namespace evoslam
