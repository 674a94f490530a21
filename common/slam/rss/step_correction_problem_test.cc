#include "common/slam/rss/step_correction_problem.h"

#include <gtest/gtest.h>

#include <memory>
#include <numbers>

#include "common/engine/algorithm_spec.h"
#include "common/localization/test_scenes.h"
#include "common/optim/evolve.h"
#include "common/slam/slam_testing.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

Eigen::Vector3d AsVector(const Pose2& p) { return {p.x(), p.y(), p.theta()}; }

// A map of the box room seen from a few poses along a walk, and the next scan of the walk.
struct Scene {
  HitCountGrid map;
  LaserScan next;
  Pose2 next_pose{3.1, 2.5, 0.8};
};

// map_width: cells of 5 cm from x = -1; the room spans x in [0, 6].
Scene MakeScene(int map_width = 180) {
  Scene s{HitCountGrid(0.05, Eigen::Vector2d(-1.0, -1.0), map_width, 200), {}};
  const LineMap room = testing::BoxRoom();
  for (int i = 0; i < 5; ++i) {
    const Pose2 pose(2.5 + 0.1 * i, 2.0 + 0.08 * i, 0.55 + 0.04 * i);
    s.map.AddScan(testing::ScanFrom(room, pose), pose);
  }
  s.next = testing::ScanFrom(room, s.next_pose);
  return s;
}

class StepCorrectionTest : public ::testing::TestWithParam<LocalFitness> {};

TEST_P(StepCorrectionTest, TheTrueCorrectionScoresBestAndPsoFindsIt) {
  const Scene s = MakeScene();
  const Pose2 odometry_error(0.12, -0.08, 3.0 * kDegree);
  const Pose2 predicted = s.next_pose * odometry_error;
  const StepCorrectionProblem problem(s.map, s.next, predicted,
                                      Eigen::Vector3d(0.2, 0.2, 5.0 * kDegree), GetParam());
  const Eigen::Vector3d truth = AsVector(odometry_error.inverse());
  EXPECT_LT((AsVector(problem.Corrected(truth)) - AsVector(s.next_pose)).norm(), 1e-12);
  const double at_truth = problem.Score(truth);
  EXPECT_LT(at_truth, problem.Score(Eigen::Vector3d::Zero()));
  for (const Eigen::Vector3d& off : {Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d(0, -0.1, 0),
                                     Eigen::Vector3d(0, 0, 2 * kDegree)}) {
    EXPECT_LT(at_truth, problem.Score(truth + off)) << off.transpose();
  }
  // Evaluate agrees with Score, whatever the batch.
  Eigen::MatrixXd batch(3, 2);
  batch << truth, Eigen::Vector3d::Zero();
  double f[2];
  problem.Evaluate(batch, f);
  EXPECT_EQ(f[0], at_truth);

  // 002's local search: PSO with 10 particles, c1 = c2 = 2.
  AlgorithmSpec spec;
  spec.kind = AlgorithmKind::kPso;
  spec.pso.particles = 10;
  spec.pso.c1 = spec.pso.c2 = 2.0;
  spec.pso.inertia = 0.7;
  const std::unique_ptr<Algorithm> pso = MakeAlgorithm(spec);
  StopCriteria stop;
  stop.max_generations = 60;
  Rng rng(3);
  const OptimResult r = Minimize(problem, *pso, stop, rng);
  const Pose2 found = problem.Corrected(r.best);
  EXPECT_LT((found.translation() - s.next_pose.translation()).norm(), 0.05);
  EXPECT_LT(std::abs(WrapAngle(found.theta() - s.next_pose.theta())), 1.0 * kDegree);
}

// Eqs. 1 and 2 as the paper writes them, nothing spared: every end point placed with Pose2, the
// cells sorted to count them. The problem must give these bits. The map's obstacles all lie in
// the part being updated, so that part's sums are the whole map's.
double ScoreAsWritten(const HitCountGrid& map, const LaserScan& scan, const Pose2& pose,
                      LocalFitness fitness) {
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector2d& p : ReturnPoints(scan)) points.push_back(pose * p);
  const testing::CountedInsertion added = testing::CountAsWritten(map, points);
  const double occupied = static_cast<double>(map.occupied() + added.fresh);
  if (fitness == LocalFitness::kEval1) return occupied;
  return occupied > 0 ? -static_cast<double>(map.total() + added.inside) / occupied : 0.0;
}

TEST_P(StepCorrectionTest, ScoresRandomCandidatesToTheBitAsTheEquationsAreWritten) {
  // The map cut short of the wall at x = 6, so that some end points fall off the grid.
  const Scene s = MakeScene(130);
  const HitCountGrid& map = s.map;
  const Pose2 predicted = s.next_pose * Pose2(0.12, -0.08, 3.0 * kDegree);
  ASSERT_GT(HitCountGrid(map).AddScan(s.next, predicted), 0u);
  const StepCorrectionProblem problem(map, s.next, predicted, Eigen::Vector3d(0.3, 0.3, 0.2),
                                      GetParam());
  Rng rng(5);
  constexpr Eigen::Index kCandidates = 200;  // enough for Evaluate to use its threads
  Eigen::MatrixXd batch(3, kCandidates);
  for (Eigen::Index i = 0; i < kCandidates; ++i) {
    for (Eigen::Index g = 0; g < 3; ++g)
      batch(g, i) = rng.Uniform(problem.lower()(g), problem.upper()(g));
  }
  std::vector<double> fitness(kCandidates);
  problem.Evaluate(batch, fitness);
  for (Eigen::Index i = 0; i < kCandidates; ++i) {
    const double want = ScoreAsWritten(map, s.next, problem.Corrected(batch.col(i)), GetParam());
    EXPECT_EQ(fitness[static_cast<std::size_t>(i)], want) << "candidate " << i;
    EXPECT_EQ(problem.Score(batch.col(i)), want) << "candidate " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(BothScores, StepCorrectionTest,
                         ::testing::Values(LocalFitness::kEval1, LocalFitness::kEval2),
                         [](const auto& info) {
                           return std::string(LocalFitnessName(info.param));
                         });

// A corridor mapped end to end, and a scan from its middle: eq. 1 pins the pose across the
// corridor and its heading, not along it.
struct Corridor {
  HitCountGrid map{0.05, Eigen::Vector2d(-12.0, -1.0), 480, 60};
  LaserScan next;
  Pose2 next_pose{0.5, 1.01, 0.0};
};

Corridor MakeCorridor() {
  Corridor c;
  const LineMap walls({{{-60.0, 0.02}, {60.0, 0.02}}, {{-60.0, 2.02}, {60.0, 2.02}}});
  for (double x = -10.0; x <= 10.0; x += 0.25) {
    const Pose2 pose(x, 1.01, 0.0);
    c.map.AddScan(testing::ScanFrom(walls, pose), pose);
  }
  c.next = testing::ScanFrom(walls, c.next_pose);
  return c;
}

// The correction PSO finds along the corridor, for a step odometry gets right.
double ShiftAlongCorridor(const Corridor& c, double pull, std::uint64_t seed) {
  const StepCorrectionProblem problem(c.map, c.next, c.next_pose,
                                      Eigen::Vector3d(0.1, 0.1, 3.0 * kDegree),
                                      LocalFitness::kEval1, pull);
  AlgorithmSpec spec;
  spec.kind = AlgorithmKind::kPso;
  spec.pso.particles = 10;
  const std::unique_ptr<Algorithm> pso = MakeAlgorithm(spec);
  StopCriteria stop;
  stop.max_generations = 30;
  Rng rng(seed);
  return Minimize(problem, *pso, stop, rng).best(0);
}

TEST(StepCorrectionProblemTest, OdometryPullKeepsAStepAlongACorridorWhereOdometryPutsIt) {
  const Corridor c = MakeCorridor();
  double loosest = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    loosest = std::max(loosest, std::abs(ShiftAlongCorridor(c, 0.0, seed)));
    EXPECT_LT(std::abs(ShiftAlongCorridor(c, 0.5, seed)), 0.005) << "seed " << seed;
  }
  // Without the pull, the swarm settles anywhere along the flat score.
  EXPECT_GT(loosest, 0.02);
}

TEST(StepCorrectionProblemTest, OdometryPullAddsUnderOneCellAndNeverOutweighsABetterFit) {
  const Scene s = MakeScene();
  const Eigen::Vector3d cube(0.2, 0.2, 5.0 * kDegree);
  const Pose2 predicted = s.next_pose * Pose2(0.12, -0.08, 3.0 * kDegree);
  const StepCorrectionProblem plain(s.map, s.next, predicted, cube, LocalFitness::kEval1);
  const StepCorrectionProblem pulled(s.map, s.next, predicted, cube, LocalFitness::kEval1, 0.9);
  Rng rng(7);
  for (int i = 0; i < 50; ++i) {
    Eigen::Vector3d e;
    for (int g = 0; g < 3; ++g) e(g) = rng.Uniform(-cube(g), cube(g));
    const double extra = pulled.Score(e) - plain.Score(e);
    EXPECT_NEAR(extra, 0.9 * e.cwiseQuotient(cube).squaredNorm() / 3.0, 1e-9);
    EXPECT_LT(extra, 0.9 + 1e-12);
  }
  EXPECT_EQ(pulled.Score(Eigen::Vector3d::Zero()), plain.Score(Eigen::Vector3d::Zero()));
  // The true correction fits better by whole cells, so the pull leaves it the best.
  const Eigen::Vector3d truth = AsVector(Pose2(0.12, -0.08, 3.0 * kDegree).inverse());
  EXPECT_LT(pulled.Score(truth), pulled.Score(Eigen::Vector3d::Zero()));
  EXPECT_THROW(StepCorrectionProblem(s.map, s.next, predicted, cube, LocalFitness::kEval1, -0.1),
               Error);
}

TEST(StepCorrectionProblemTest, Eval1CountsTheCellsTheScanLeavesOccupied) {
  HitCountGrid map(1.0, Eigen::Vector2d(-10, -10), 20, 20);
  map.Add({3.5, 0.5});    // where the first beam ends
  map.Add({-8.5, -8.5});  // far away: outside the part being updated
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = std::numbers::pi / 2;
  scan.range_min = 0.1;
  scan.range_max = 10.0;
  scan.ranges = {3.0, 3.0, 3.0};  // ends at (3, 0), (0, 3), (-3, 0) seen from (0.5, 0.5)
  const StepCorrectionProblem eval1(map, scan, Pose2(0.5, 0.5, 0.0), Eigen::Vector3d::Zero(),
                                    LocalFitness::kEval1);
  // One cell already occupied, two new.
  EXPECT_EQ(eval1.Score(Eigen::Vector3d::Zero()), 3.0);
  const StepCorrectionProblem eval2(map, scan, Pose2(0.5, 0.5, 0.0), Eigen::Vector3d::Zero(),
                                    LocalFitness::kEval2);
  // Four observations over three cells.
  EXPECT_DOUBLE_EQ(eval2.Score(Eigen::Vector3d::Zero()), -4.0 / 3.0);
  EXPECT_THROW(
      StepCorrectionProblem(map, scan, Pose2(), Eigen::Vector3d(-1, 0, 0), LocalFitness::kEval1),
      Error);
  EXPECT_THROW(ParseLocalFitness("eval3"), Error);
}

}  // namespace
}  // namespace evoslam
