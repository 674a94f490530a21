#include "common/slam/immune/key_points.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "common/io/carmen_reader.h"
#include "common/sim/sim_testing.h"
#include "common/sim/simulator.h"
#include "common/slam/immune/scan_gaps.h"
#include "common/util/error.h"
#include "common/util/error_testing.h"

namespace evoslam {
namespace {

using ::testing::HasSubstr;

constexpr double kKeyTestMaxRange = 3.0;  // the method's cut (004 §4)

// Two square pillars, 0.6 m wide, in a 10 x 8 m room; their corners are the room's only convex
// ones (the room's own are concave).
struct KeyTestPillarRoom {
  static constexpr double kHalfSide = 0.3;
  static std::array<Eigen::Vector2d, 2> Centres() { return {{{3.5, 4.0}, {6.5, 4.0}}}; }

  static std::vector<Eigen::Vector2d> ConvexCorners() {
    std::vector<Eigen::Vector2d> corners;
    for (const Eigen::Vector2d& c : Centres()) {
      for (const double sx : {-1.0, 1.0}) {
        for (const double sy : {-1.0, 1.0}) {
          corners.push_back(c + kHalfSide * Eigen::Vector2d(sx, sy));
        }
      }
    }
    return corners;
  }

  static LineMap Map() {
    const LineMap room = testing::Room(10.0, 8.0);
    std::vector<Segment> walls(room.segments().begin(), room.segments().end());
    for (const Eigen::Vector2d& c : Centres()) {
      const double h = kHalfSide;
      const Eigen::Vector2d a = c + Eigen::Vector2d(-h, -h), b = c + Eigen::Vector2d(h, -h),
                            d = c + Eigen::Vector2d(h, h), e = c + Eigen::Vector2d(-h, h);
      walls.insert(walls.end(), {{a, b}, {b, d}, {d, e}, {e, a}});
    }
    return LineMap(walls);
  }

  // Around both pillars, 1 m from their faces, once each way: so that the forward-looking laser
  // sees every corner against open space within the 1.5 m at which eq. 6 with delta_Key = 1 parts
  // an edge from open space cut at 3 m.
  static Dataset Drive() {
    World world{"pillars",
                Map(),
                {{1.5, 2.7},
                 {8.5, 2.7},
                 {8.5, 5.3},
                 {1.5, 5.3},
                 {1.5, 2.7},
                 {1.5, 5.3},
                 {8.5, 5.3},
                 {8.5, 2.7},
                 {1.5, 2.7}}};
    SimulationOptions options;
    options.laser.beams = 181;
    options.noise.gaussian_sigma = 0.01;
    return Simulate(world, options);
  }
};

std::vector<Pose2> KeyTestTruePoses(const Dataset& dataset) {
  std::vector<Pose2> poses;
  for (const LaserScan& scan : dataset.scans) poses.push_back(*scan.true_pose);
  return poses;
}

double KeyTestDistanceToNearest(const Eigen::Vector2d& p,
                                const std::vector<Eigen::Vector2d>& points) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& q : points) nearest = std::min(nearest, (p - q).norm());
  return nearest;
}

TEST(FindKeyPointsTest, DrivePastPillarsFindsTheirCornersAndNothingElse) {
  const Dataset drive = KeyTestPillarRoom::Drive();
  const proto::KeyPointParams params;
  const std::vector<KeyPoint> key_points =
      FindKeyPoints(drive, KeyTestTruePoses(drive), params, kKeyTestMaxRange);
  const double two_cells = 2 * params.cell_size_m();
  std::vector<Eigen::Vector2d> found;
  for (const KeyPoint& k : key_points) {
    EXPECT_LE(KeyTestDistanceToNearest(k.position, KeyTestPillarRoom::ConvexCorners()), two_cells)
        << k.position.transpose();
    EXPECT_GE(k.belief, params.confirm_belief());
    found.push_back(k.position);
  }
  for (const Eigen::Vector2d& corner : KeyTestPillarRoom::ConvexCorners()) {
    EXPECT_LE(KeyTestDistanceToNearest(corner, found), two_cells) << corner.transpose();
  }
  // One key point a corner: candidates around the same corner are merged.
  EXPECT_EQ(key_points.size(), KeyTestPillarRoom::ConvexCorners().size());
}

// In the office cluster (furnished offices off a hallway, entered through ten doors) every key
// point is a wall's end: a door jamb or a corner of the furniture, none in free space or along a
// wall. The route passes through every door, whose two jambs stand against open space.
TEST(FindKeyPointsTest, OfficeClusterKeyPointsAreWallEnds) {
  const World world = BuiltinWorld("office-cluster");
  SimulationOptions options;
  options.laser.beams = 181;
  options.noise.gaussian_sigma = 0.01;
  const Dataset drive = Simulate(world, options);
  const proto::KeyPointParams params;
  const std::vector<KeyPoint> key_points =
      FindKeyPoints(drive, KeyTestTruePoses(drive), params, kKeyTestMaxRange);
  std::vector<Eigen::Vector2d> wall_ends;
  for (const Segment& wall : world.map.segments()) {
    wall_ends.push_back(wall.a);
    wall_ends.push_back(wall.b);
  }
  EXPECT_GE(key_points.size(), 20u);
  for (const KeyPoint& k : key_points) {
    EXPECT_LE(KeyTestDistanceToNearest(k.position, wall_ends), 2 * params.cell_size_m())
        << k.position.transpose();
  }
}

// Each sighting is a gap that its scan sees, placed where its pose puts it; a key point's
// sightings and the key points themselves come in scan order.
TEST(FindKeyPointsTest, SightingsAreTheScansGapsInOrder) {
  const Dataset drive = KeyTestPillarRoom::Drive();
  const std::vector<Pose2> poses = KeyTestTruePoses(drive);
  const proto::KeyPointParams params;
  const std::vector<KeyPoint> key_points = FindKeyPoints(drive, poses, params, kKeyTestMaxRange);
  ASSERT_FALSE(key_points.empty());
  for (std::size_t k = 0; k < key_points.size(); ++k) {
    const std::vector<KeyPointSighting>& sightings = key_points[k].sightings;
    ASSERT_GE(sightings.size(), 3u);
    if (k > 0) {
      EXPECT_LT(key_points[k - 1].sightings.front().scan, sightings.front().scan);
    }
    for (std::size_t i = 0; i < sightings.size(); ++i) {
      const KeyPointSighting& s = sightings[i];
      if (i > 0) {
        EXPECT_LE(sightings[i - 1].scan, s.scan);
      }
      const std::vector<ScanGap> gaps = FindScanGaps(drive.scans[s.scan], params, kKeyTestMaxRange);
      EXPECT_TRUE(std::ranges::any_of(
          gaps, [&](const ScanGap& g) { return g.beam == s.beam && g.point == s.point; }));
      const double cell = params.cell_size_m();
      EXPECT_LE(((poses[s.scan] * s.point) - key_points[k].position).cwiseAbs().maxCoeff(),
                1.5 * cell + 1e-9);
    }
  }
}

// A laser at `pose` in the pillar room, the same scan `count` times.
Dataset KeyTestStandingStill(const Pose2& pose, std::size_t count) {
  const LineMap map = KeyTestPillarRoom::Map();
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 180;
  scan.range_max = 8.0;
  for (int i = 0; i <= 180; ++i) {
    scan.ranges.push_back(
        static_cast<float>(map.CastRay(pose.translation(), pose.theta() + scan.angle(i), 8.0)));
  }
  Dataset dataset;
  dataset.scans.assign(count, scan);
  return dataset;
}

// Below pillar A, 1 m from its face: both lower corners are edges against open space.
const Pose2 kKeyTestBelowPillar(3.5, 2.7, std::numbers::pi / 2);

TEST(FindKeyPointsTest, OneViewpointConfirmsNothing) {
  const Dataset still = KeyTestStandingStill(kKeyTestBelowPillar, 30);
  ASSERT_FALSE(FindScanGaps(still.scans[0], {}, kKeyTestMaxRange).empty());
  const std::vector<Pose2> poses(still.scans.size(), kKeyTestBelowPillar);
  EXPECT_TRUE(FindKeyPoints(still, poses, {}, kKeyTestMaxRange).empty());
  // Counted as independent, the same sightings would confirm.
  proto::KeyPointParams every_sighting;
  every_sighting.set_min_view_shift_m(0.0);
  EXPECT_FALSE(FindKeyPoints(still, poses, every_sighting, kKeyTestMaxRange).empty());
}

TEST(FindKeyPointsTest, TurningOnTheSpotConfirmsNothing) {
  Dataset turning;
  std::vector<Pose2> poses;
  for (int i = 0; i < 30; ++i) {
    const Pose2 pose(kKeyTestBelowPillar.translation(),
                     kKeyTestBelowPillar.theta() + (i - 15) * 0.02);
    turning.scans.push_back(KeyTestStandingStill(pose, 1).scans[0]);
    poses.push_back(pose);
  }
  EXPECT_TRUE(FindKeyPoints(turning, poses, {}, kKeyTestMaxRange).empty());
}

TEST(FindKeyPointsTest, UsesTheScansItHasPosesFor) {
  const Dataset drive = KeyTestPillarRoom::Drive();
  const std::vector<Pose2> poses = KeyTestTruePoses(drive);
  const std::size_t half = poses.size() / 2;
  const std::vector<KeyPoint> key_points =
      FindKeyPoints(drive, std::span(poses).first(half), {}, kKeyTestMaxRange);
  ASSERT_FALSE(key_points.empty());
  EXPECT_LT(key_points.size(), FindKeyPoints(drive, poses, {}, kKeyTestMaxRange).size());
  for (const KeyPoint& k : key_points) EXPECT_LT(k.sightings.back().scan, half);
  EXPECT_TRUE(FindKeyPoints(drive, {}, {}, kKeyTestMaxRange).empty());
}

TEST(FindKeyPointsTest, RefusesMorePosesThanScansAndABadRange) {
  const Dataset still = KeyTestStandingStill(kKeyTestBelowPillar, 2);
  const std::vector<Pose2> poses(3);
  EXPECT_THAT(testing::ErrorOf([&] { FindKeyPoints(still, poses, {}, kKeyTestMaxRange); }),
              HasSubstr("3 poses for 2 scans"));
  EXPECT_THAT(testing::ErrorOf([&] { FindKeyPoints(still, {}, {}, 0.0); }),
              HasSubstr("maximum range"));
}

TEST(ValidateKeyPointParamsTest, NamesTheField) {
  EXPECT_NO_THROW(ValidateKeyPointParams({}));
  const auto error_of = [](auto set) {
    proto::KeyPointParams params;
    set(params);
    return testing::ErrorOf([&] { ValidateKeyPointParams(params); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using P = proto::KeyPointParams;
  EXPECT_THAT(error_of([](P& p) { p.set_section_ratio(0.0); }),
              HasSubstr("key_points.section_ratio"));
  EXPECT_THAT(error_of([&](P& p) { p.set_section_ratio(nan); }),
              HasSubstr("key_points.section_ratio"));
  EXPECT_THAT(error_of([](P& p) { p.set_min_section_points(0); }),
              HasSubstr("key_points.min_section_points"));
  EXPECT_THAT(error_of([](P& p) { p.set_min_gap_m(-0.1); }), HasSubstr("key_points.min_gap_m"));
  EXPECT_THAT(error_of([](P& p) { p.set_cell_size_m(0.0); }), HasSubstr("key_points.cell_size_m"));
  EXPECT_THAT(error_of([](P& p) { p.set_sighting_belief(1.0); }),
              HasSubstr("key_points.sighting_belief"));
  EXPECT_THAT(error_of([](P& p) { p.set_sighting_belief(0.0); }),
              HasSubstr("key_points.sighting_belief"));
  EXPECT_THAT(error_of([](P& p) { p.set_confirm_belief(1.0); }),
              HasSubstr("key_points.confirm_belief"));
  EXPECT_THAT(error_of([&](P& p) { p.set_min_view_shift_m(nan); }),
              HasSubstr("key_points.min_view_shift_m"));
  EXPECT_THAT(error_of([](P& p) { p.set_min_view_shift_m(-1.0); }),
              HasSubstr("key_points.min_view_shift_m"));
}

// Intel's raw log with its drifting odometry: 004's setting, key points computed once per log.
// Each key point stands apart from the others and is confirmed by as many sightings from
// viewpoints min_view_shift_m apart as its belief says. The time taken is recorded.
TEST(FindKeyPointsRealDataTest, IntelWithOdometry) {
  const auto path = std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const Dataset log = ReadCarmen(path);
  std::vector<Pose2> odometry;
  for (const LaserScan& scan : log.scans) odometry.push_back(scan.odometry);
  const proto::KeyPointParams params;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<KeyPoint> key_points = FindKeyPoints(log, odometry, params, kKeyTestMaxRange);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  ::testing::Test::RecordProperty("seconds", std::to_string(took.count()));
  ::testing::Test::RecordProperty("key_points", static_cast<int>(key_points.size()));
  ASSERT_FALSE(key_points.empty());
  for (std::size_t k = 0; k < key_points.size(); ++k) {
    const KeyPoint& key = key_points[k];
    for (std::size_t j = 0; j < k; ++j) {
      const Eigen::Vector2d apart = key.position - key_points[j].position;
      EXPECT_GT(apart.cwiseAbs().maxCoeff(), 2.5 * params.cell_size_m());
    }
    std::vector<Eigen::Vector2d> viewpoints;
    for (const KeyPointSighting& s : key.sightings) {
      const Eigen::Vector2d v = odometry[s.scan].translation();
      if (std::ranges::all_of(viewpoints, [&](const Eigen::Vector2d& u) {
            return (u - v).norm() >= params.min_view_shift_m();
          })) {
        viewpoints.push_back(v);
      }
    }
    const double belief =
        1.0 - std::pow(1.0 - params.sighting_belief(), static_cast<double>(viewpoints.size()));
    EXPECT_DOUBLE_EQ(key.belief, belief);
    EXPECT_GE(key.belief, params.confirm_belief());
  }
}

}  // namespace
}  // namespace evoslam
