#include "common/localization/scan_fitness.h"

#include <gtest/gtest.h>

#include <numbers>

#include "common/localization/segment_renderer.h"
#include "common/localization/test_scenes.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(ShiftLayoutTest, HalfDegreeBeamsAndHeadingSteps) {
  LaserScan scan;
  scan.angle_min = -90 * kDegree;
  scan.angle_increment = 0.5 * kDegree;
  scan.ranges.assign(361, 1.0f);
  const ShiftLayout l = MakeShiftLayout(scan, 30 * kDegree, 0.5 * kDegree);
  EXPECT_EQ(l.shifts, 121u);
  EXPECT_EQ(l.beam_stride, 1u);
  EXPECT_EQ(l.shift_stride, 1u);
  EXPECT_EQ(l.rays, 481u);  // 240 degrees of rays
  EXPECT_NEAR(l.first_offset, -120 * kDegree, 1e-12);
  EXPECT_NEAR(l.shift_angle(0), -30 * kDegree, 1e-12);
  EXPECT_NEAR(l.shift_angle(120), 30 * kDegree, 1e-12);
}

TEST(ShiftLayoutTest, OneDegreeBeamsInterleaveHalfDegreeHeadings) {
  LaserScan scan;
  scan.angle_min = -90 * kDegree;
  scan.angle_increment = 1 * kDegree;
  scan.ranges.assign(180, 1.0f);
  const ShiftLayout l = MakeShiftLayout(scan, 10 * kDegree, 0.5 * kDegree);
  EXPECT_EQ(l.beam_stride, 2u);
  EXPECT_EQ(l.shift_stride, 1u);
  EXPECT_EQ(l.shifts, 41u);
  EXPECT_EQ(l.rays, 179u * 2 + 40 + 1);
}

TEST(ShiftLayoutTest, FineBeamsUseSeveralRaysPerHeadingStep) {
  LaserScan scan;
  scan.angle_increment = 0.25 * kDegree;
  scan.ranges.assign(721, 1.0f);
  const ShiftLayout l = MakeShiftLayout(scan, 5 * kDegree, 0.5 * kDegree);
  EXPECT_EQ(l.shift_stride, 2u);
  EXPECT_EQ(l.shifts, 21u);
  EXPECT_NEAR(l.shift_angle(20) - l.shift_angle(19), 0.5 * kDegree, 1e-12);
}

TEST(ShiftLayoutTest, RejectsUnusableScans) {
  LaserScan scan;
  scan.ranges.assign(1, 1.0f);
  scan.angle_increment = kDegree;
  EXPECT_THROW(MakeShiftLayout(scan, 0.1, 0.01), Error);
}

class BestShiftTest : public ::testing::TestWithParam<FitnessKind> {};

// A scan taken at heading h + 7.5 degrees is found at shift +15 of a window centred on h.
TEST_P(BestShiftTest, RecoversHeadingOffset) {
  const LineMap map = testing::BoxRoom();
  const Pose2 truth(2.5, 3.0, 0.4 + 7.5 * kDegree);
  const LaserScan scan = testing::ScanFrom(map, truth);
  const ShiftLayout layout = MakeShiftLayout(scan, 30 * kDegree, 0.5 * kDegree);
  const float max_range = 8.0f;
  const ObservedBeams observed = PrepareObservation(scan, max_range);
  const SegmentRenderer renderer(TemporaryMap(map, truth.translation(), 9.0));
  const RayFan fan(0.4 + layout.first_offset, layout.ray_step, layout.rays);
  std::vector<float> rays(layout.rays), sums(layout.shifts);
  renderer.Render(truth.translation(), fan, max_range, rays);
  FitnessParams params;
  params.kind = GetParam();
  const ShiftScore best = BestShift(params, layout, observed, rays, max_range, sums);
  EXPECT_EQ(best.shift, 60u + 15u);
  if (params.kind == FitnessKind::kF3) {
    EXPECT_LT(best.fitness, 0.05);
  } else {
    EXPECT_LE(best.fitness, -0.95 * static_cast<double>(observed.index.size()));
  }
  // Every other heading scores worse (F2, a count, may tie next to the optimum).
  for (std::size_t k = 0; k < layout.shifts; ++k) {
    if (k == best.shift) continue;
    if (params.kind == FitnessKind::kF3) {
      EXPECT_GT(sums[k], best.fitness);
    } else {
      EXPECT_GE(sums[k], best.fitness);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(F2AndF3, BestShiftTest,
                         ::testing::Values(FitnessKind::kF3, FitnessKind::kF2));

TEST(ScanFitnessTest, LeavesOutBeamsWithoutReturnOnEitherSide) {
  LaserScan scan;
  scan.angle_increment = kDegree;
  scan.range_max = 8.0;
  scan.ranges = {1.0f, 8.0f, 2.0f, 0.0f};  // beam 1: no return, beam 3: invalid zero
  const ObservedBeams observed = PrepareObservation(scan, 8.0f);
  ASSERT_EQ(observed.index.size(), 2u);
  EXPECT_EQ(observed.index[0], 0u);
  EXPECT_EQ(observed.index[1], 2u);
  FitnessParams f3;
  // Simulated: beam 0 off by 0.5, beam 2 finds nothing within range (left out).
  const std::vector<float> rays = {1.5f, 3.0f, 8.0f, 1.0f};
  EXPECT_FLOAT_EQ(ScoreAligned(f3, observed, rays, 8.0f), 0.5f);
  FitnessParams f2;
  f2.kind = FitnessKind::kF2;
  const std::vector<float> close = {1.02f, 3.0f, 2.01f, 1.0f};
  EXPECT_FLOAT_EQ(ScoreAligned(f2, observed, close, 8.0f), -2.0f);
  const std::vector<float> far = {1.2f, 3.0f, 2.01f, 1.0f};
  EXPECT_FLOAT_EQ(ScoreAligned(f2, observed, far, 8.0f), -1.0f);
}

TEST(ScanFitnessTest, F3sCapBoundsEachBeamsTerm) {
  LaserScan scan;
  scan.angle_increment = kDegree;
  scan.range_max = 30.0;
  scan.ranges = {1.0f, 2.0f, 3.0f};
  const ObservedBeams observed = PrepareObservation(scan, 30.0f);
  // Beam 0 off by 0.25 m, beam 1 by 5 m (a person the map lacks), beam 2 by 0.5 m.
  const std::vector<float> rays = {1.25f, 7.0f, 2.5f};
  FitnessParams f3;
  EXPECT_FLOAT_EQ(ScoreAligned(f3, observed, rays, 30.0f), 5.75f);
  f3.f3_cap = 0.4;
  EXPECT_FLOAT_EQ(ScoreAligned(f3, observed, rays, 30.0f), 0.25f + 0.4f + 0.4f);

  // The heading search scores alike: one beam per shift, so each shift's sum is one term.
  const ShiftLayout layout = MakeShiftLayout(scan, 0.0, kDegree);
  ASSERT_EQ(layout.shifts, 1u);
  std::vector<float> sums(1);
  EXPECT_FLOAT_EQ(BestShift(f3, layout, observed, rays, 30.0f, sums).fitness, 1.05f);
  f3.f3_cap = 0.0;
  EXPECT_FLOAT_EQ(BestShift(f3, layout, observed, rays, 30.0f, sums).fitness, 5.75f);
}

// A beam whose simulated range jumps between neighbouring candidates (a ray that slips past a
// door frame, a wall the grid draws ragged at a grazing angle) can outweigh a whole scan in the
// uncapped sum; capped, it counts no more than one beam that misses.
TEST(ScanFitnessTest, CappedF3KeepsTheHeadingTheRestOfTheScanAgreesOn) {
  LaserScan scan;
  scan.angle_increment = kDegree;
  scan.range_max = 30.0;
  scan.ranges = {2.0f, 2.2f, 2.4f, 2.6f, 2.8f};
  const ObservedBeams observed = PrepareObservation(scan, 30.0f);
  const ShiftLayout layout = MakeShiftLayout(scan, kDegree, kDegree);
  ASSERT_EQ(layout.shifts, 3u);
  ASSERT_EQ(layout.rays, 7u);
  // At the centre (beam j reads ray j + 1) four beams fit exactly and the last misses by 4 m;
  // one step to the right (ray j) every beam is 0.2 m off; one to the left (ray j + 2), four
  // are 0.2 m off and one misses by 4.2 m.
  const std::vector<float> rays = {1.8f, 2.0f, 2.2f, 2.4f, 2.6f, 6.8f, 3.0f};
  std::vector<float> sums(layout.shifts);
  FitnessParams f3;
  const ShiftScore uncapped = BestShift(f3, layout, observed, rays, 30.0f, sums);
  EXPECT_EQ(uncapped.shift, 0u);
  EXPECT_NEAR(uncapped.fitness, 1.0, 1e-5);
  f3.f3_cap = 0.3;
  const ShiftScore capped = BestShift(f3, layout, observed, rays, 30.0f, sums);
  EXPECT_EQ(capped.shift, 1u);
  EXPECT_NEAR(capped.fitness, 0.3, 1e-5);
  EXPECT_NEAR(sums[0], 1.0, 1e-5);
  EXPECT_NEAR(sums[2], 0.2 * 4 + 0.3, 1e-5);
}

TEST(ScanFitnessTest, ParsesNames) {
  EXPECT_EQ(ParseFitnessKind("f2"), FitnessKind::kF2);
  EXPECT_EQ(FitnessKindName(ParseFitnessKind("f3")), "f3");
  EXPECT_THROW(ParseFitnessKind("f4"), Error);
}

}  // namespace
}  // namespace evoslam
