#include "common/localization/segment_renderer.h"

#include <gtest/gtest.h>

#include <numbers>

#include "common/localization/test_scenes.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// The sweep must agree with casting every ray through the map one at a time.
void ExpectMatchesRayCasting(const LineMap& map, const Eigen::Vector2d& origin, const RayFan& fan,
                             float max_range) {
  const SegmentRenderer renderer(TemporaryMap(map, origin, max_range + 1.0));
  std::vector<float> rays(fan.size());
  renderer.Render(origin, fan, max_range, rays);
  for (std::size_t i = 0; i < fan.size(); ++i) {
    const double angle = fan.first_angle + static_cast<double>(i) * fan.step;
    const double expected = map.CastRay(origin, angle, max_range);
    ASSERT_NEAR(rays[i], expected, 2e-4) << "ray " << i << " angle " << angle;
  }
}

TEST(SegmentRendererTest, MatchesRayCastingInBoxRoom) {
  const LineMap map = testing::BoxRoom();
  Rng rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector2d origin(rng.Uniform(0.2, 5.8), rng.Uniform(0.2, 7.8));
    const double first = rng.Uniform(-4, 4);
    const RayFan fan(first, 0.5 * std::numbers::pi / 180, 481);
    ExpectMatchesRayCasting(map, origin, fan, 8.0f);
  }
}

TEST(SegmentRendererTest, FansWiderThanAFullTurnRepeatTheCircle) {
  const LineMap map = testing::BoxRoom();
  const RayFan fan(2.0, 0.5 * std::numbers::pi / 180, 1081);  // 540 degrees
  ExpectMatchesRayCasting(map, {3.0, 4.0}, fan, 8.0f);
}

TEST(SegmentRendererTest, RandomWallsAndShortRange) {
  Rng rng(2);
  std::vector<Segment> walls;
  for (int i = 0; i < 80; ++i) {
    const Eigen::Vector2d a(rng.Uniform(0, 20), rng.Uniform(0, 20));
    const Eigen::Vector2d b = a + Eigen::Vector2d(rng.Uniform(-3, 3), rng.Uniform(-3, 3));
    walls.push_back({a, b});
  }
  const LineMap map(walls);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector2d origin(rng.Uniform(0, 20), rng.Uniform(0, 20));
    ExpectMatchesRayCasting(map, origin, RayFan(rng.Uniform(-3, 3), 0.01, 300), 4.0f);
  }
}

TEST(SegmentRendererTest, EmptyMapReadsMaxRange) {
  const SegmentRenderer renderer({});
  std::vector<float> rays(10, 0.0f);
  renderer.Render({0, 0}, RayFan(0, 0.1, 10), 8.0f, rays);
  for (float r : rays) EXPECT_EQ(r, 8.0f);
}

TEST(TemporaryMapTest, KeepsOnlyWallsInReach) {
  const LineMap map = testing::BoxRoom();
  const auto near = TemporaryMap(map, {1.3, 1.2}, 0.5);
  EXPECT_EQ(near.size(), 4u);  // the box around (1.3, 1.2) only
  EXPECT_EQ(TemporaryMap(map, {3, 4}, 20).size(), map.size());
}

}  // namespace
}  // namespace evoslam
