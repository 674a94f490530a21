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

}  // namespace evoslam::testing
