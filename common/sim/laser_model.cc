#include "common/sim/laser_model.h"

#include <cmath>

#include <fmt/format.h>

#include "common/transform/angle_units.h"
#include "common/util/error.h"

namespace evoslam {

double LaserModel::angle_min() const { return -0.5 * Radians(field_of_view_deg); }

double LaserModel::angle_increment() const {
  return beams > 1 ? Radians(field_of_view_deg) / (beams - 1) : 0.0;
}

void CheckLaserModel(const LaserModel& laser) {
  if (laser.beams < 1) throw Error(fmt::format("laser: beams must be >= 1, got {}", laser.beams));
  if (!(laser.field_of_view_deg > 0.0 && laser.field_of_view_deg <= 360.0)) {
    throw Error(fmt::format("laser: field of view must be in (0, 360] degrees, got {}",
                            laser.field_of_view_deg));
  }
  if (!(laser.min_range >= 0.0 && laser.min_range < laser.max_range) ||
      !std::isfinite(laser.max_range)) {
    throw Error(
        fmt::format("laser: ranges must satisfy 0 <= min_range < max_range < inf, got "
                    "min_range {} and max_range {}",
                    laser.min_range, laser.max_range));
  }
}

}  // namespace evoslam
