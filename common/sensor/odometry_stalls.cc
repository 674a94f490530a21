#include "common/sensor/odometry_stalls.h"

#include <cmath>
#include <string>

#include "common/util/error.h"

namespace evoslam {

namespace {

bool SamePosition(const Pose2& a, const Pose2& b) { return a.x() == b.x() && a.y() == b.y(); }

}  // namespace

std::vector<OdometryStall> FindOdometryStalls(std::span<const LaserScan> scans,
                                              const Eigen::Vector3d& absorbed) {
  std::vector<OdometryStall> stalls;
  std::size_t i = 1;
  while (i < scans.size()) {
    if (!SamePosition(scans[i].odometry, scans[i - 1].odometry)) {
      ++i;
      continue;
    }
    std::size_t end = i;  // the first scan past the run of repeats
    bool heading_held = true;
    while (end < scans.size() && SamePosition(scans[end].odometry, scans[end - 1].odometry)) {
      heading_held = heading_held && scans[end].odometry.theta() == scans[end - 1].odometry.theta();
      ++end;
    }
    if (end < scans.size()) {
      const Pose2 catch_up = scans[i - 1].odometry.inverse() * scans[end].odometry;
      // Where the heading read on, its change over the run is the robot's own turn, no catch-up.
      if (std::abs(catch_up.x()) > absorbed.x() || std::abs(catch_up.y()) > absorbed.y() ||
          (heading_held && std::abs(catch_up.theta()) > absorbed.z())) {
        stalls.push_back({i, end - 1, catch_up, heading_held});
      }
    }
    i = end;
  }
  return stalls;
}

void FillOdometryStalls(std::span<LaserScan> scans, std::span<const OdometryStall> stalls) {
  for (const OdometryStall& stall : stalls) {
    if (stall.first == 0 || stall.first > stall.last || stall.last + 1 >= scans.size()) {
      throw Error("odometry stall: scans " + std::to_string(stall.first) + " to " +
                  std::to_string(stall.last) + " have no reading either side in a log of " +
                  std::to_string(scans.size()) + " scans");
    }
    const LaserScan& before = scans[stall.first - 1];
    const LaserScan& after = scans[stall.last + 1];
    const double span = after.timestamp - before.timestamp;
    bool timed = span > 0.0;
    for (std::size_t k = stall.first; k <= stall.last + 1 && timed; ++k) {
      timed = scans[k].timestamp > scans[k - 1].timestamp;
    }
    const double steps = static_cast<double>(stall.last + 2 - stall.first);
    for (std::size_t k = stall.first; k <= stall.last; ++k) {
      const double s = timed ? (scans[k].timestamp - before.timestamp) / span
                             : static_cast<double>(k + 1 - stall.first) / steps;
      const Pose2 spread = Interpolate(before.odometry, after.odometry, s);
      scans[k].odometry =
          stall.heading_held ? spread : Pose2(spread.translation(), scans[k].odometry.theta());
    }
  }
}

}  // namespace evoslam
