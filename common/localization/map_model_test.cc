#include "common/localization/map_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "common/grid/map_io.h"
#include "common/localization/localizer.h"
#include "common/localization/ray_fan.h"
#include "common/localization/test_scenes.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

// A grid of the box room built the way --map-from-log builds one: noiseless scans inserted at
// their true poses along a loop through the room.
OccupancyGrid BoxRoomGrid(double resolution) {
  const LineMap map = testing::BoxRoom();
  std::vector<LaserScan> scans;
  std::vector<Pose2> poses;
  for (int i = 0; i < 72; ++i) {
    const double a = i * 5 * kDegree;
    const Pose2 p(3.0 + 1.2 * std::cos(a), 4.0 + 2.0 * std::sin(a), a + std::numbers::pi / 2);
    scans.push_back(testing::ScanFrom(map, p));
    poses.push_back(p);
  }
  return OccupancyGrid::FromScans(scans, poses, resolution, 1.0);
}

TEST(MapModelTest, GridRendererAgreesWithTheWalls) {
  const LineMap walls = testing::BoxRoom();
  const MapModel lines(walls);
  const MapModel grid(BoxRoomGrid(0.02));
  const RayFan fan(-std::numbers::pi, 0.5 * kDegree, 720);
  std::vector<float> from_lines(fan.size()), from_grid(fan.size());
  for (const Eigen::Vector2d& origin : {Eigen::Vector2d(3.0, 4.0), Eigen::Vector2d(2.2, 2.5)}) {
    lines.LocalRenderer(origin, 8.5)->Render(origin, fan, 8.0f, from_lines);
    grid.LocalRenderer(origin, 8.5)->Render(origin, fan, 8.0f, from_grid);
    int close = 0;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      // A wall's cells start up to a cell diagonal before it; grazing rays may differ more.
      close += std::abs(from_lines[i] - from_grid[i]) < 0.06f;
    }
    EXPECT_GT(close, static_cast<int>(0.95 * fan.size())) << origin.transpose();
  }
}

TEST(MapModelTest, LocalizesInAGridMap) {
  const MapModel map(BoxRoomGrid(0.02));
  Dataset d;
  d.source = "synthetic";
  for (int i = 0; i < 20; ++i) {
    const double s = 0.05 * i;
    LaserScan scan = testing::ScanFrom(testing::BoxRoom(), Pose2(2.5 + s, 2.2 + 0.8 * s, 0.4));
    scan.timestamp = i;
    d.scans.push_back(std::move(scan));
  }
  const LocalizeResult r = Localize(map, d, {});
  ASSERT_EQ(r.trajectory.size(), d.scans.size());
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    const Pose2& truth = *d.scans[i].true_pose;
    EXPECT_LT((r.trajectory[i].pose.translation() - truth.translation()).norm(), 0.03) << i;
    EXPECT_NEAR(WrapAngle(r.trajectory[i].pose.theta() - truth.theta()), 0.0, 1.0 * kDegree) << i;
  }
}

TEST(MapModelTest, LoadsLinesOrGridByExtension) {
  const TempDir dir;
  WriteLineMap(testing::BoxRoom(), dir / "room.lines");
  WriteMapYaml(BoxRoomGrid(0.05), dir / "room.yaml");
  const MapModel lines = LoadMapModel(dir / "room.lines");
  ASSERT_NE(lines.walls(), nullptr);
  EXPECT_EQ(lines.grid(), nullptr);
  EXPECT_EQ(lines.walls()->size(), testing::BoxRoom().size());
  const MapModel grid = LoadMapModel(dir / "room.yaml");
  ASSERT_NE(grid.grid(), nullptr);
  EXPECT_EQ(grid.walls(), nullptr);
  EXPECT_NEAR(grid.grid()->resolution(), 0.05, 1e-12);
  EXPECT_THROW(LoadMapModel(dir / "absent.yaml"), Error);
  EXPECT_THROW(LoadMapModel(dir / "absent.lines"), Error);
}

}  // namespace
}  // namespace evoslam
