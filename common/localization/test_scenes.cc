#include "common/localization/test_scenes.h"

#include <numbers>
#include <vector>

namespace evoslam::testing {
namespace {

void AddBox(std::vector<Segment>& walls, double x0, double y0, double x1, double y1) {
  walls.push_back({{x0, y0}, {x1, y0}});
  walls.push_back({{x1, y0}, {x1, y1}});
  walls.push_back({{x1, y1}, {x0, y1}});
  walls.push_back({{x0, y1}, {x0, y0}});
}

}  // namespace

LineMap BoxRoom() {
  std::vector<Segment> walls;
  AddBox(walls, 0, 0, 6, 8);
  AddBox(walls, 1.0, 1.0, 1.6, 1.4);
  AddBox(walls, 4.2, 2.5, 4.6, 3.1);
  AddBox(walls, 2.0, 5.5, 3.2, 5.9);
  walls.push_back({{4.5, 6.0}, {6.0, 7.2}});
  return LineMap(std::move(walls));
}

LaserScan ScanFrom(const LineMap& map, const Pose2& pose, int beams, double max_range) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / (beams % 2 ? beams - 1 : beams);
  scan.range_max = max_range;
  scan.pose = scan.odometry = pose;
  scan.true_pose = pose;
  for (int i = 0; i < beams; ++i) {
    const double r = map.CastRay(pose.translation(), pose.theta() + scan.angle(i), max_range);
    scan.ranges.push_back(static_cast<float>(r));
  }
  return scan;
}

Dataset WalkThroughBoxRoom(int scans) {
  const LineMap map = BoxRoom();
  Dataset d;
  d.source = "synthetic";
  for (int i = 0; i < scans; ++i) {
    const double s = i * 0.05;
    const Pose2 p(2.5 + s, 2.0 + 0.6 * s, 0.55 + 0.3 * s);
    LaserScan scan = ScanFrom(map, p);
    scan.timestamp = 1000.0 + 0.2 * i;
    scan.odometry = Pose2(2.5 + 1.1 * s, 2.0 + 0.66 * s, 0.55 + 0.33 * s);
    scan.pose = scan.odometry;
    d.scans.push_back(std::move(scan));
  }
  return d;
}

}  // namespace evoslam::testing
