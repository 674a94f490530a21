#include "common/slam/immune/trajectory_segments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

// A drive along x in steps of `step` m, turning `turn` rad a step.
std::vector<Pose2> Drive(std::size_t scans, double step, double turn = 0.0) {
  std::vector<Pose2> poses = {Pose2(1.0, -2.0, 0.3)};
  for (std::size_t k = 1; k < scans; ++k) poses.push_back(poses.back() * Pose2(step, 0.0, turn));
  return poses;
}

proto::TrajectorySegmentParams Params() { return {}; }

TEST(TrajectorySegmentsTest, SegmentsEndAfterTheirLengthAndCoverEveryStep) {
  const std::vector<Pose2> poses = Drive(101, 0.1);  // 10 m
  const auto segments = CutSegments(poses, {}, Params());
  ASSERT_EQ(segments.size(), 7u);  // 6 of 1.5 m (15 steps), then the last 1 m
  std::size_t first = 0;
  for (const TrajectorySegment& s : segments) {
    EXPECT_EQ(s.first, first);
    EXPECT_GT(s.last, s.first);
    first = s.last;
  }
  EXPECT_EQ(first, poses.size() - 1);
  for (std::size_t j = 0; j + 1 < segments.size(); ++j) {
    EXPECT_NEAR(segments[j].length, 1.5, 0.1 + 1e-9) << j;
  }
  EXPECT_NEAR(segments.back().length, 10.0 - 6 * 1.5, 0.1);
}

TEST(TrajectorySegmentsTest, TurnsEndASegmentEarly) {
  const std::vector<Pose2> poses = Drive(41, 0.01, 0.05);  // 0.4 m, 2 rad
  proto::TrajectorySegmentParams params = Params();
  params.set_max_turn_rad(0.5);
  const auto segments = CutSegments(poses, {}, params);
  ASSERT_EQ(segments.size(), 4u);
  for (const TrajectorySegment& s : segments) EXPECT_NEAR(s.turn, 0.5, 1e-9);
}

TEST(TrajectorySegmentsTest, SegmentsAroundAKeyPointSightingAreShort) {
  const std::vector<Pose2> poses = Drive(101, 0.05);  // 5 m
  const std::vector<std::size_t> fine = {50};
  const auto segments = CutSegments(poses, fine, Params());
  const auto holding = std::find_if(segments.begin(), segments.end(),
                                    [](const auto& s) { return s.first <= 50 && 50 < s.last; });
  ASSERT_NE(holding, segments.end());
  EXPECT_NEAR(holding->length, 0.2, 0.05 + 1e-9);
  // Without the sighting, that stretch is one long segment.
  const auto plain = CutSegments(poses, {}, Params());
  EXPECT_LT(plain.size(), segments.size());
}

TEST(TrajectorySegmentsTest, NoCorrectionGivesTheTrajectoryBack) {
  const std::vector<Pose2> poses = Drive(60, 0.07, 0.02);
  const SegmentedTrajectory trajectory(poses, CutSegments(poses, {}, Params()));
  const std::vector<SegmentCorrection> none(trajectory.segments().size());
  const std::vector<Pose2> again = trajectory.AllPoses(none);
  ASSERT_EQ(again.size(), poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_NEAR(again[k].x(), poses[k].x(), 1e-9) << k;
    EXPECT_NEAR(again[k].y(), poses[k].y(), 1e-9) << k;
    EXPECT_NEAR(again[k].theta(), poses[k].theta(), 1e-9) << k;
  }
}

TEST(TrajectorySegmentsTest, ACorrectionStretchesAndBendsItsSegmentAndCarriesTheRest) {
  const std::vector<Pose2> poses = Drive(31, 0.1);  // 3 m straight: segments of 1.5 m
  const SegmentedTrajectory trajectory(poses, CutSegments(poses, {}, Params()));
  ASSERT_EQ(trajectory.segments().size(), 2u);
  std::vector<SegmentCorrection> corrections(2);
  corrections[0].length = 0.15;  // the first segment 10 % longer
  const std::vector<Pose2> longer = trajectory.AllPoses(corrections);
  const std::size_t cut = trajectory.segments()[0].last;
  EXPECT_NEAR((longer[cut].translation() - poses[0].translation()).norm(), 1.65, 1e-9);
  // The second segment moves rigidly with the end of the first.
  EXPECT_NEAR((longer.back().translation() - longer[cut].translation()).norm(), 1.5, 1e-9);
  EXPECT_NEAR(longer.back().theta(), poses.back().theta(), 1e-12);

  corrections[0] = {.length = 0.0, .turn = 0.2};
  const std::vector<Pose2> bent = trajectory.AllPoses(corrections);
  EXPECT_NEAR(bent[cut].theta(), WrapAngle(poses[cut].theta() + 0.2), 1e-12);
  EXPECT_NEAR(bent.back().theta(), WrapAngle(poses.back().theta() + 0.2), 1e-12);
  EXPECT_NEAR((bent[cut].translation() - poses[0].translation()).norm(),
              (poses[cut].translation() - poses[0].translation()).norm() * std::sin(0.1) / 0.1,
              0.01);
}

TEST(TrajectorySegmentsTest, PosesOfAWindowMatchThoseOfTheWhole) {
  const std::vector<Pose2> poses = Drive(91, 0.1, 0.01);
  const SegmentedTrajectory trajectory(poses, CutSegments(poses, {}, Params()));
  ASSERT_GE(trajectory.segments().size(), 4u);
  std::vector<SegmentCorrection> corrections(trajectory.segments().size());
  for (std::size_t j = 0; j < corrections.size(); ++j) {
    corrections[j] = {.length = 0.01 * static_cast<double>(j), .turn = -0.02};
  }
  const std::vector<Pose2> all = trajectory.AllPoses(corrections);
  const TrajectorySegment& a = trajectory.segments()[1];
  const TrajectorySegment& b = trajectory.segments()[2];
  std::vector<Pose2> window(b.last - a.first + 1);
  trajectory.Poses(1, std::span(corrections).subspan(1, 2), all[a.first], window);
  for (std::size_t k = 0; k < window.size(); ++k) EXPECT_EQ(window[k], all[a.first + k]) << k;
}

TEST(TrajectorySegmentsTest, RefusesSegmentsThatDoNotCoverTheTrajectory) {
  const std::vector<Pose2> poses = Drive(10, 0.1);
  EXPECT_THROW(SegmentedTrajectory(poses, {{.first = 0, .last = 5}}), Error);
  EXPECT_THROW(SegmentedTrajectory(poses, {{.first = 1, .last = 9}}), Error);
  EXPECT_TRUE(CutSegments(std::span(poses).first(1), {}, Params()).empty());
}

TEST(TrajectorySegmentsTest, ValidationNamesTheField) {
  proto::TrajectorySegmentParams params = Params();
  params.set_length_m(0);
  try {
    ValidateTrajectorySegmentParams(params);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("length_m"), std::string::npos) << e.what();
  }
  params = Params();
  params.set_encoding("binary");
  EXPECT_THROW(ValidateTrajectorySegmentParams(params), Error);
  EXPECT_NO_THROW(ValidateTrajectorySegmentParams(Params()));
}

}  // namespace
}  // namespace evoslam
