#include "common/slam/place_matcher.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

Dataset Drive() {
  SimulationOptions sim;
  sim.laser.beams = 91;
  sim.max_scans = 40;
  return Simulate(BuiltinWorld("office-cluster"), sim);
}

// The place: scans [0, 20) at their true poses.
PlaceMatcher PlaceOf(const Dataset& d) {
  std::vector<LaserScan> scans(d.scans.begin(), d.scans.begin() + 20);
  std::vector<Pose2> poses;
  for (const LaserScan& s : scans) poses.push_back(*s.true_pose);
  return PlaceMatcher(scans, poses, 0.05, 0.1, 1.0);
}

TEST(PlaceMatcherTest, FindsAScanOfThePlaceFromAFarGuess) {
  const Dataset d = Drive();
  const PlaceMatcher place = PlaceOf(d);
  const LaserScan& scan = d.scans[10];
  const Pose2 truth = *scan.true_pose;
  const std::vector<Eigen::Vector2d> points = ReturnPoints(scan);
  const Pose2 guess = truth * Pose2(0.6, -0.4, 0.2);
  const PlaceMatcher::Match m = place.Search(points, guess, 1.0, 0.3, 0.3);
  EXPECT_LT((m.pose.translation() - truth.translation()).norm(), 0.03);
  EXPECT_LT(std::abs(WrapAngle(m.pose.theta() - truth.theta())), 0.01);
  EXPECT_GT(m.score, 0.8);
  EXPECT_LT(place.Score(points, guess), 0.5 * m.score);
  // The office's furniture pins the pose down: nowhere 0.3 m away matches nearly as well.
  EXPECT_GT(m.distinctness, 0.2);
  // Outside the window it cannot be found.
  const PlaceMatcher::Match narrow = place.Search(points, guess, 0.2, 0.05, 0.1);
  EXPECT_GT((narrow.pose.translation() - truth.translation()).norm(), 0.2);
}

// A drive down a corridor, along world x, with nothing but its two long walls in the laser's
// reach; the place is every scan at its true pose.
struct Corridor {
  Dataset log;
  PlaceMatcher place;
};

Corridor DriveDownACorridor() {
  const World corridor = WorldFromLineMap(LineMap({{{0, 0}, {40, 0}}, {{0, 2}, {40, 2}}}),
                                          "corridor", {{2, 1}, {38, 1}});
  SimulationOptions sim;
  sim.laser.max_range = 4.0;
  sim.max_scans = 60;
  Dataset log = Simulate(corridor, sim);
  std::vector<Pose2> poses;
  for (const LaserScan& s : log.scans) poses.push_back(*s.true_pose);
  PlaceMatcher place(log.scans, poses, 0.05, 0.1, 1.0);
  return {std::move(log), std::move(place)};
}

// Such a corridor matches as well anywhere along it: the best pose is no better than its
// rivals, which a loop detector must not trust.
TEST(PlaceMatcherTest, AFeaturelessCorridorIsNotDistinct) {
  const Corridor c = DriveDownACorridor();
  const PlaceMatcher& place = c.place;
  const LaserScan& scan = c.log.scans[30];
  const PlaceMatcher::Match m =
      place.Search(ReturnPoints(scan), *scan.true_pose * Pose2(0.5, 0.1, 0.05), 1.0, 0.3, 0.3);
  EXPECT_GT(m.score, 0.8);          // it fits...
  EXPECT_LT(m.distinctness, 0.02);  // ...but as well 0.3 m or more along the corridor
}

// The coarse lattice's headings are shared out among threads; the match must not depend on how.
TEST(PlaceMatcherTest, TheMatchIsTheSameBitsWhateverTheThreadCount) {
  const Dataset d = Drive();
  const PlaceMatcher place = PlaceOf(d);
  const LaserScan& scan = d.scans[10];
  const int saved = omp_get_max_threads();
  std::vector<PlaceMatcher::Match> matches;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    // A 1.5 m window: enough work for the coarse lattice to be shared out.
    matches.push_back(
        place.Search(ReturnPoints(scan), *scan.true_pose * Pose2(0.6, -0.4, 0.2), 1.5, 0.3, 0.3));
  }
  omp_set_num_threads(saved);
  for (const PlaceMatcher::Match& m : matches) {
    EXPECT_EQ(m.pose.translation(), matches[0].pose.translation());
    EXPECT_EQ(m.pose.theta(), matches[0].pose.theta());
    EXPECT_EQ(m.score, matches[0].score);
    EXPECT_EQ(m.distinctness, matches[0].distinctness);
  }
  EXPECT_GT(matches[0].score, 0.8);
}

TEST(PlaceMatcherTest, ScoresAreMeanLikelihoods) {
  const Dataset d = Drive();
  const PlaceMatcher place = PlaceOf(d);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(d.scans[5]);
  const double at_truth = place.Score(points, *d.scans[5].true_pose);
  EXPECT_GT(at_truth, 0.9);
  EXPECT_LE(at_truth, 1.0);
  EXPECT_EQ(place.Score({}, *d.scans[5].true_pose), 0.0);
  // Far from the place no return lands near an obstacle.
  EXPECT_EQ(place.Score(points, Pose2(500, 500, 0)), 0.0);
}

TEST(PlaceMatcherTest, ALatticeOfWholeCellStepsScoresAsEachPoseWould) {
  const Dataset d = Drive();
  // A place of one scan with a narrow margin: many points of a scan taken further on fall off
  // its field, at every translation of the lattice (the sanitizers watch those reads).
  const PlaceMatcher place(std::span(d.scans).first(1), std::vector<Pose2>{*d.scans[0].true_pose},
                           0.05, 0.1, 0.2);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(d.scans[15]);
  const Pose2 center = *d.scans[15].true_pose * Pose2(0.13, -0.07, 0.0);
  constexpr int kHalf = 12;
  std::vector<double> scores;
  // 2 cells (the shortcut), 1 cell, and 0.75 cells (scored pose by pose).
  for (const double step : {0.1, 0.05, 0.0375}) {
    for (const double theta : {-2.0, center.theta(), 3.1}) {
      place.ScoreTranslations(points, center, theta, step, kHalf, scores);
      ASSERT_EQ(scores.size(), static_cast<std::size_t>((2 * kHalf + 1) * (2 * kHalf + 1)));
      for (int iy = -kHalf; iy <= kHalf; ++iy) {
        for (int ix = -kHalf; ix <= kHalf; ++ix) {
          const Pose2 pose(center.x() + ix * step, center.y() + iy * step, theta);
          EXPECT_NEAR(scores[static_cast<std::size_t>((iy + kHalf) * (2 * kHalf + 1) + ix + kHalf)],
                      place.Score(points, pose), 1e-9)
              << "step " << step << " theta " << theta << " at " << ix << ", " << iy;
        }
      }
    }
    // At the scan's own heading the lattice reaches where the two scans overlap.
    place.ScoreTranslations(points, center, center.theta(), step, kHalf, scores);
    EXPECT_GT(*std::max_element(scores.begin(), scores.end()), 0.2) << "step " << step;
  }
}

// A wall 2 m ahead across the laser's view, as one scan sees it.
LaserScan ScanOfAWallAhead() {
  LaserScan scan;
  scan.angle_min = -0.6;
  scan.angle_increment = 0.01;
  scan.range_max = 8.0;
  for (int i = 0; i <= 120; ++i) {
    scan.ranges.push_back(static_cast<float>(2.0 / std::cos(scan.angle(i))));
  }
  return scan;
}

// The same wall seen from the far side lines up with the place's returns as well, and no return
// agrees with the side the place saw it from.
TEST(PlaceMatcherTest, AWallSeenFromItsFarSideScoresButDisagrees) {
  const LaserScan scan = ScanOfAWallAhead();
  const std::vector<LaserScan> scans = {scan};
  const std::vector<Pose2> poses = {Pose2(0.0, 0.0, 0.0)};
  const PlaceMatcher place(scans, poses, 0.05, 0.1, 1.0);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(scan);
  const Pose2 behind(4.0, 0.0, std::numbers::pi);
  EXPECT_GT(place.Score(points, poses[0]), 0.9);
  EXPECT_GT(place.Score(points, behind), 0.9);
  EXPECT_EQ(place.SideAgreement(points, poses[0]), 1.0);
  EXPECT_EQ(place.SideAgreement(points, behind), 0.0);
  // Returns that land far from every return of the place say nothing either way.
  EXPECT_EQ(place.SideAgreement(points, Pose2(0.0, 5.0, 0.0)), 1.0);
}

// The wall y = 1 (world frame) as a scan from `pose` sees it, out to 6 m.
LaserScan ScanOfTheWallYIsOne(const Pose2& pose) {
  LaserScan scan;
  scan.angle_min = -1.5;
  scan.angle_increment = 0.01;
  scan.range_max = 8.0;
  for (int i = 0; i <= 300; ++i) {
    const double heading = pose.theta() + scan.angle(i);
    const double rise = std::sin(heading);
    const double range = rise > 0.0 ? (1.0 - pose.y()) / rise : 0.0;
    scan.ranges.push_back(static_cast<float>(range > 0.0 && range < 6.0 ? range : 8.0));
  }
  return scan;
}

// A corridor's wall seen from the corridor's two ends: the two scans' beams meet it heading in
// nearly opposite directions, from the same side.
TEST(PlaceMatcherTest, AWallSeenFromEitherEndOfACorridorAgrees) {
  const Pose2 west(0.0, 0.0, 0.0), east(5.0, 0.0, std::numbers::pi);
  const std::vector<LaserScan> scans = {ScanOfTheWallYIsOne(west)};
  const std::vector<Pose2> poses = {west};
  const PlaceMatcher place(scans, poses, 0.05, 0.1, 1.0);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(ScanOfTheWallYIsOne(east));
  ASSERT_GT(points.size(), 100u);
  EXPECT_GT(place.Score(points, east), 0.5);
  EXPECT_GT(place.SideAgreement(points, east), 0.95);
}

TEST(PlaceMatcherTest, RefusesMismatchedInputs) {
  const Dataset d = Drive();
  const std::vector<LaserScan> scans(d.scans.begin(), d.scans.begin() + 2);
  const std::vector<Pose2> one = {Pose2()};
  EXPECT_THROW(PlaceMatcher(scans, one, 0.05, 0.1, 1.0), Error);
  const std::vector<Pose2> two = {Pose2(), Pose2()};
  EXPECT_THROW(PlaceMatcher(scans, two, 0.0, 0.1, 1.0), Error);
  EXPECT_THROW(PlaceMatcher(scans, two, 0.05, -1.0, 1.0), Error);
}

}  // namespace
}  // namespace evoslam
