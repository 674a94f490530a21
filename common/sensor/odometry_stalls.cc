#include "common/sensor/odometry_stalls.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <string>

#include "common/util/error.h"

namespace evoslam {

namespace {

// Calls `run(first, end)` for each run of scans [first, end) over which `same(scan k, scan k - 1)`
// holds: end is the scan that ends it, or the number of scans where it lasts to the end.
template <typename Same, typename Run>
void ForEachRun(std::span<const LaserScan> scans, Same same, Run run) {
  std::size_t i = 1;
  while (i < scans.size()) {
    if (!same(scans[i].odometry, scans[i - 1].odometry)) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < scans.size() && same(scans[end].odometry, scans[end - 1].odometry)) ++end;
    run(i, end);
    i = end;
  }
}

Pose2 CatchUp(std::span<const LaserScan> scans, std::size_t first, std::size_t end) {
  return scans[first - 1].odometry.inverse() * scans[end].odometry;
}

bool SamePosition(const Pose2& a, const Pose2& b) { return a.x() == b.x() && a.y() == b.y(); }

bool MovesBeyond(const Pose2& catch_up, const Eigen::Vector3d& absorbed) {
  return std::abs(catch_up.x()) > absorbed.x() || std::abs(catch_up.y()) > absorbed.y();
}

}  // namespace

std::vector<OdometryStall> FindRepeatedReadings(std::span<const LaserScan> scans) {
  std::vector<OdometryStall> runs;
  ForEachRun(scans, std::equal_to<Pose2>(), [&](std::size_t first, std::size_t end) {
    if (end < scans.size()) runs.push_back({first, end - 1, CatchUp(scans, first, end)});
  });
  return runs;
}

std::vector<OdometryStall> FindOdometryStalls(std::span<const LaserScan> scans,
                                              const Eigen::Vector3d& absorbed) {
  const std::vector<OdometryStall> repeats = FindRepeatedReadings(scans);
  auto repeat = repeats.begin();
  std::vector<OdometryStall> stalls;
  ForEachRun(scans, SamePosition, [&](std::size_t first, std::size_t end) {
    // The repeated readings within this run of repeated positions.
    const auto within_end = std::find_if(repeat, repeats.end(),
                                         [end](const OdometryStall& r) { return r.first >= end; });
    if (end < scans.size() && MovesBeyond(CatchUp(scans, first, end), absorbed)) {
      bool heading_held = true;
      for (std::size_t k = first; k < end; ++k) {
        heading_held = heading_held && scans[k].odometry.theta() == scans[k - 1].odometry.theta();
      }
      stalls.push_back({first, end - 1, CatchUp(scans, first, end), heading_held});
    } else {
      // The position moved on by little (standing, or turning on the spot): a stall is a run of
      // whole readings held up within it, a turn most likely, that the cube cannot follow.
      std::copy_if(repeat, within_end, std::back_inserter(stalls), [&](const OdometryStall& r) {
        return MovesBeyond(r.catch_up, absorbed) || std::abs(r.catch_up.theta()) > absorbed.z();
      });
    }
    repeat = within_end;
  });
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
