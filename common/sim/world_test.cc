#include "common/sim/world.h"
#include "common/sim/sim_testing.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/line_map/segment_geometry.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::Room;

using ::testing::HasSubstr;

Eigen::Vector2d Size(const World& world) { return world.map.bounds().max - world.map.bounds().min; }

TEST(WorldTest, EveryBuiltinWorldBuilds) {
  const std::vector<std::string> names = BuiltinWorldNames();
  ASSERT_EQ(names.size(), 5u);
  for (const std::string& name : names) {
    const World world = BuiltinWorld(name);
    EXPECT_EQ(world.name, name);
    EXPECT_FALSE(world.map.empty()) << name;
    EXPECT_GE(world.waypoints.size(), 2u) << name;
    EXPECT_GT(world.scan_spacing, 0.0) << name;
    // Every waypoint lies inside the map's bounds and away from the walls.
    for (const Eigen::Vector2d& p : world.waypoints) {
      EXPECT_TRUE(world.map.SegmentsNear(p, kMinWallClearance).empty())
          << name << " waypoint " << p.transpose();
    }
  }
}

TEST(WorldTest, BuiltinWorldsHaveThePapersDimensions) {
  const World boxes = BuiltinWorld("office-boxes");
  EXPECT_EQ(boxes.map.size(), 60u);
  EXPECT_TRUE(Size(boxes).isApprox(Eigen::Vector2d(10, 10)));

  const World cluster = BuiltinWorld("office-cluster");
  EXPECT_NEAR(static_cast<double>(cluster.map.size()), 329.0, 5.0);
  EXPECT_TRUE(Size(cluster).isApprox(Eigen::Vector2d(25.6, 18.8)));

  for (const char* name : {"s-corridor", "static-objects", "empty-room"}) {
    const Eigen::Vector2d size = Size(BuiltinWorld(name));
    EXPECT_NEAR(std::min(size.x(), size.y()), 6.0, 0.3) << name;
    EXPECT_NEAR(std::max(size.x(), size.y()), 8.0, 0.3) << name;
  }
  EXPECT_EQ(BuiltinWorld("empty-room").map.size(), 4u);
  EXPECT_GE(BuiltinWorld("static-objects").map.size(), 40u);  // many objects
}

// The cluster's ten 5.12 x 8.4 m offices: five along each side of the hallway.
void ExpectRouteEntersEveryOffice(const World& world) {
  for (int office = 0; office < 10; ++office) {
    const double x0 = (office % 5) * 5.12;
    const double y0 = office < 5 ? 0.0 : 10.4;
    bool entered = false;
    for (const Eigen::Vector2d& p : world.waypoints) {
      entered = entered || (p.x() > x0 && p.x() < x0 + 5.12 && p.y() > y0 && p.y() < y0 + 8.4);
    }
    EXPECT_TRUE(entered) << "office " << office;
  }
}

TEST(WorldTest, OfficeClusterRouteEntersEveryOffice) {
  const World world = BuiltinWorld("office-cluster");
  ExpectRouteEntersEveryOffice(world);
}

TEST(WorldTest, UnknownNameListsTheBuiltins) {
  try {
    BuiltinWorld("moon-base");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("moon-base"));
    EXPECT_THAT(e.what(), HasSubstr("office-cluster"));
  }
}

TEST(WorldFromLineMapTest, KeepsGivenWaypoints) {
  const World world = WorldFromLineMap(Room(8, 6), "room", {{1, 1}, {7, 5}});
  EXPECT_EQ(world.name, "room");
  ASSERT_EQ(world.waypoints.size(), 2u);
  EXPECT_EQ(world.waypoints[1], Eigen::Vector2d(7, 5));
  EXPECT_EQ(world.scan_spacing, kDefaultScanSpacing);
}

TEST(WorldFromLineMapTest, AutoRouteLoopsAroundTheRoom) {
  const World world = WorldFromLineMap(Room(8, 6));
  ASSERT_GE(world.waypoints.size(), 4u);
  EXPECT_TRUE(world.waypoints.front().isApprox(world.waypoints.back()));
  double length = 0.0;
  for (std::size_t i = 0; i < world.waypoints.size(); ++i) {
    const Eigen::Vector2d& p = world.waypoints[i];
    EXPECT_GT(p.x(), 0.5);
    EXPECT_LT(p.x(), 7.5);
    EXPECT_GT(p.y(), 0.5);
    EXPECT_LT(p.y(), 5.5);
    if (i > 0) {
      const Segment leg{world.waypoints[i - 1], p};
      EXPECT_GE(WallClearance(world.map, leg, 1.0), kMinWallClearance);
      length += (p - world.waypoints[i - 1]).norm();
    }
  }
  // About the rectangle 0.6 m inside the walls: 2 * (6.8 + 4.8).
  EXPECT_NEAR(length, 23.2, 2.0);
}

TEST(WorldFromLineMapTest, AutoRouteVisitsEveryOfficeOfTheCluster) {
  const World world = WorldFromLineMap(BuiltinWorld("office-cluster").map);
  ExpectRouteEntersEveryOffice(world);
}

TEST(WorldFromLineMapTest, RejectsBadInput) {
  EXPECT_THROW(WorldFromLineMap(LineMap()), Error);
  // An open wall encloses nothing.
  EXPECT_THROW(WorldFromLineMap(LineMap({{{0, 0}, {10, 0}}})), Error);
  // A room too small to keep clear of its walls.
  EXPECT_THROW(WorldFromLineMap(Room(1, 1)), Error);
  EXPECT_THROW(WorldFromLineMap(Room(8, 6), "x", {{1, 1}, {std::nan(""), 2}}), Error);
}

}  // namespace
}  // namespace evoslam
