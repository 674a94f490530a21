#include "common/eval/trajectory_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace evoslam {
namespace {

std::vector<StampedPose> Square() {
  std::vector<StampedPose> t;
  for (int i = 0; i < 40; ++i) {
    const double a = i * 0.1;
    t.push_back({100.0 + 0.2 * i, Pose2(std::cos(a) * 3, std::sin(a) * 3, a + 1.0)});
  }
  return t;
}

Eigen::Vector2d Centroid(const std::vector<StampedPose>& trajectory) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const StampedPose& p : trajectory) sum += p.pose.translation();
  return sum / static_cast<double>(trajectory.size());
}

TEST(AbsoluteErrorsTest, ZeroForIdenticalTrajectories) {
  const auto t = Square();
  const AbsoluteErrors e = ComputeAbsoluteErrors(t, t);
  EXPECT_EQ(e.poses, t.size());
  EXPECT_EQ(e.rms_translation, 0.0);
  EXPECT_EQ(e.rms_theta, 0.0);
}

TEST(AbsoluteErrorsTest, RmsPerAxisOfKnownOffsets) {
  const auto truth = Square();
  auto est = truth;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const double sign = i % 2 ? 1.0 : -1.0;  // +-3 cm in x, 4 cm in y, 0.5 deg in heading
    const Pose2& p = est[i].pose;
    est[i].pose =
        Pose2(p.x() + sign * 0.03, p.y() + 0.04, p.theta() + sign * 0.5 * std::numbers::pi / 180);
  }
  const AbsoluteErrors e = ComputeAbsoluteErrors(est, truth);
  EXPECT_NEAR(e.rms_x, 0.03, 1e-12);
  EXPECT_NEAR(e.rms_y, 0.04, 1e-12);
  EXPECT_NEAR(e.rms_theta, 0.5 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(e.rms_translation, 0.05, 1e-12);
  EXPECT_NEAR(e.max_translation, 0.05, 1e-12);
  // The +-3 cm in x alternate and cancel; the 4 cm in y is a shift the alignment takes out.
  EXPECT_NEAR(e.aligned_rms_translation, 0.03, 1e-3);
}

TEST(AbsoluteErrorsTest, PairsByTimestampNotByIndex) {
  const auto truth = Square();
  std::vector<StampedPose> est(truth.rbegin(), truth.rend());
  est.push_back({5.0, Pose2()});  // no truth at this time
  const AbsoluteErrors e = ComputeAbsoluteErrors(est, truth);
  EXPECT_EQ(e.poses, truth.size());
  EXPECT_EQ(e.unmatched, 1u);
  EXPECT_EQ(e.rms_translation, 0.0);
}

TEST(AbsoluteErrorsTest, AlignedErrorLeavesOutARigidMotion) {
  const auto truth = Square();
  std::vector<StampedPose> moved = truth;
  const Pose2 offset(5.0, -2.0, 0.7);
  for (auto& p : moved) p.pose = offset * p.pose;
  const AbsoluteErrors e = ComputeAbsoluteErrors(moved, truth);
  EXPECT_GT(e.rms_translation, 1.0);
  EXPECT_NEAR(e.aligned_rms_translation, 0.0, 1e-9);
}

TEST(AbsoluteErrorsTest, AlignedErrorOfATrajectoryDrawnTooLarge) {
  // Drawn 10 % too large about its centroid, then moved: no rigid motion undoes the scale, and the
  // best one undoes the move, which leaves a tenth of each position's distance from the centroid.
  const auto truth = Square();
  const Eigen::Vector2d centroid = Centroid(truth);
  std::vector<StampedPose> estimate = truth;
  double expected = 0.0;
  const Pose2 offset(-1.0, 4.0, -2.1);
  for (StampedPose& p : estimate) {
    const Eigen::Vector2d from_centroid = p.pose.translation() - centroid;
    expected += (0.1 * from_centroid).squaredNorm();
    const Eigen::Vector2d drawn = centroid + 1.1 * from_centroid;
    p.pose = offset * Pose2(drawn.x(), drawn.y(), p.pose.theta());
  }
  expected = std::sqrt(expected / static_cast<double>(truth.size()));
  const AbsoluteErrors e = ComputeAbsoluteErrors(estimate, truth);
  EXPECT_NEAR(e.aligned_rms_translation, expected, 1e-9);
  EXPECT_GT(expected, 0.1);
  EXPECT_GT(e.rms_translation, 3.0);
  // A similarity undoes the scale too, and says by how much it shrank the estimate.
  EXPECT_NEAR(e.scale_aligned_rms_translation, 0.0, 1e-9);
  EXPECT_NEAR(e.alignment_scale, 1 / 1.1, 1e-12);
}

TEST(AbsoluteErrorsTest, ScaleAlignedErrorKeepsWhatNoScaleExplains) {
  // Alternating +-3 cm across a circle's radius: shrinking or growing the estimate would bring
  // half its poses closer and the other half farther, so the best scale is 1 and the error stays.
  const auto truth = Square();
  auto estimate = truth;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const Pose2& p = estimate[i].pose;
    const Eigen::Vector2d outward = p.translation().normalized();
    const Eigen::Vector2d moved = p.translation() + (i % 2 ? 0.03 : -0.03) * outward;
    estimate[i].pose = Pose2(moved.x(), moved.y(), p.theta());
  }
  const AbsoluteErrors e = ComputeAbsoluteErrors(estimate, truth);
  EXPECT_NEAR(e.alignment_scale, 1.0, 1e-3);
  EXPECT_NEAR(e.scale_aligned_rms_translation, e.aligned_rms_translation, 1e-4);
  EXPECT_NEAR(e.scale_aligned_rms_translation, 0.03, 2e-3);
}

TEST(AbsoluteErrorsTest, AnEstimateStandingStillHasNoScaleToFind) {
  const auto truth = Square();
  auto estimate = truth;
  for (StampedPose& p : estimate) p.pose = Pose2(1.0, 2.0, 0.0);
  const AbsoluteErrors e = ComputeAbsoluteErrors(estimate, truth);
  EXPECT_EQ(e.alignment_scale, 1.0);
  EXPECT_NEAR(e.scale_aligned_rms_translation, e.aligned_rms_translation, 1e-12);
  // Every position aligned to one point: the error is the truth's spread about its centroid.
  const Eigen::Vector2d centroid = Centroid(truth);
  double spread = 0.0;
  for (const StampedPose& p : truth) spread += (p.pose.translation() - centroid).squaredNorm();
  EXPECT_NEAR(e.aligned_rms_translation, std::sqrt(spread / static_cast<double>(truth.size())),
              1e-9);
}

TEST(RelationErrorsTest, MeasuresRelativeNotAbsoluteError) {
  const auto truth = Square();
  // A rigidly moved copy has no relative error at all.
  std::vector<StampedPose> moved = truth;
  const Pose2 offset(5.0, -2.0, 0.7);
  for (auto& p : moved) p.pose = offset * p.pose;
  const auto relations = RelationsFromTruth(truth);
  const RelationErrors rigid = ComputeRelationErrors(moved, relations);
  EXPECT_EQ(rigid.relations, truth.size() - 1);
  EXPECT_NEAR(rigid.translation_mean, 0.0, 1e-9);
  EXPECT_NEAR(rigid.rotation_mean, 0.0, 1e-9);
}

TEST(RelationErrorsTest, KnownErrorPerRelation) {
  // Truth moves 1 m forward per step; the estimate 1.1 m and turns 0.01 rad more per step.
  std::vector<StampedPose> est;
  std::vector<Relation> relations;
  Pose2 p;
  for (int i = 0; i < 10; ++i) {
    est.push_back({static_cast<double>(i), p});
    p = p * Pose2(1.1, 0.0, 0.01);
    if (i > 0) relations.push_back({i - 1.0, static_cast<double>(i), Pose2(1.0, 0.0, 0.0)});
  }
  relations.push_back({100.0, 101.0, Pose2()});  // outside the trajectory
  const RelationErrors e = ComputeRelationErrors(est, relations);
  EXPECT_EQ(e.relations, 9u);
  EXPECT_EQ(e.skipped, 1u);
  // E = (1.1, 0, 0.01) * (1, 0, 0)^-1 = (1.1 - cos 0.01, -sin 0.01, 0.01).
  const double expected = std::hypot(1.1 - std::cos(0.01), std::sin(0.01));
  EXPECT_NEAR(e.translation_mean, expected, 1e-9);
  EXPECT_NEAR(e.translation_std, 0.0, 1e-9);
  EXPECT_NEAR(e.rotation_mean, 0.01, 1e-9);
  EXPECT_NEAR(e.translation_sq_mean, expected * expected, 1e-9);
}

TEST(RelationErrorsTest, StandardDeviationOverRelations) {
  std::vector<StampedPose> est = {{0, Pose2()}, {1, Pose2(1, 0, 0)}, {2, Pose2(3, 0, 0)}};
  std::vector<Relation> rel = {{0, 1, Pose2(1, 0, 0)}, {1, 2, Pose2(1, 0, 0)}};
  const RelationErrors e = ComputeRelationErrors(est, rel);
  EXPECT_NEAR(e.translation_mean, 0.5, 1e-12);  // errors 0 and 1
  EXPECT_NEAR(e.translation_std, 0.5, 1e-12);
}

TEST(TrajectoryIndexTest, MatchesWithinTolerance) {
  const std::vector<StampedPose> t = {{10.0, Pose2(1, 0, 0)}, {10.5, Pose2(2, 0, 0)}};
  const TrajectoryIndex index(t, 1e-3);
  ASSERT_TRUE(index.At(10.0005));
  EXPECT_EQ(index.At(10.0005)->x(), 1.0);
  EXPECT_EQ(index.At(10.4999)->x(), 2.0);
  EXPECT_FALSE(index.At(10.25));
  EXPECT_FALSE(index.At(9.0));
}

}  // namespace
}  // namespace evoslam
