#include "common/sim/crowd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/sim/sim_testing.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

using testing::Room;

using std::numbers::pi;

TEST(CrowdTest, WalksClearOfWallsAtItsSpeed) {
  const LineMap room = Room(8, 6);
  Rng rng(9);
  Crowd crowd(room, 6, 0.25, 1.0, rng);
  ASSERT_EQ(crowd.positions().size(), 6u);
  std::vector<Eigen::Vector2d> before(crowd.positions().begin(), crowd.positions().end());
  double moved = 0.0;
  for (int step = 0; step < 500; ++step) {
    crowd.Advance(room, 0.2, rng);
    for (std::size_t i = 0; i < before.size(); ++i) {
      const Eigen::Vector2d p = crowd.positions()[i];
      const double d = (p - before[i]).norm();
      EXPECT_LE(d, 0.2 + 1e-12);
      moved += d;
      EXPECT_TRUE(room.SegmentsNear(p, 0.25).empty()) << p.transpose();
      before[i] = p;
    }
  }
  // They keep walking: most of the time at full speed.
  EXPECT_GT(moved, 0.5 * 6 * 500 * 0.2);
}

TEST(CrowdTest, CastRayMeetsTheNearestDisc) {
  const LineMap room = Room(8, 6);
  Rng rng(1);
  const Crowd crowd(room, 1, 0.25, 1.0, rng);
  const Eigen::Vector2d c = crowd.positions()[0];
  EXPECT_NEAR(crowd.CastRay(c + Eigen::Vector2d(3, 0), pi, 10.0), 2.75, 1e-12);
  EXPECT_NEAR(crowd.CastRay(c - Eigen::Vector2d(0, 2), pi / 2, 10.0), 1.75, 1e-12);
  // Grazing the disc's edge from 2 m off its centre line at 0.2 m: chord geometry.
  EXPECT_NEAR(crowd.CastRay(c + Eigen::Vector2d(-2, 0.2), 0.0, 10.0),
              2.0 - std::sqrt(0.25 * 0.25 - 0.2 * 0.2), 1e-12);
  EXPECT_EQ(crowd.CastRay(c + Eigen::Vector2d(-2, 0.3), 0.0, 10.0), 10.0);  // passes by
  EXPECT_EQ(crowd.CastRay(c + Eigen::Vector2d(3, 0), 0.0, 10.0), 10.0);     // facing away
  EXPECT_EQ(crowd.CastRay(c + Eigen::Vector2d(3, 0), pi, 2.0), 2.0);        // beyond range
  EXPECT_EQ(crowd.CastRay(c, 0.0, 10.0), 10.0);                             // from inside
}

TEST(CrowdTest, NoRoomThrows) {
  Rng rng(1);
  EXPECT_THROW(Crowd(Room(0.4, 0.4), 1, 0.25, 1.0, rng), Error);
}

}  // namespace
}  // namespace evoslam
