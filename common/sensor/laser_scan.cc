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

}  // namespace evoslam
