#include "common/slam/rss/global_search_problem.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/slam_testing.h"
#include "common/util/error.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

TEST(GlobalSearchProblemTest, TheIdentityChangesNothingAndErrorsSpreadOverTheirPartition) {
  SimulationOptions sim;
  sim.laser.beams = 31;
  sim.max_scans = 30;
  const struct { Dataset log; } loop{Simulate(BuiltinWorld("office-cluster"), sim)};
  const std::size_t n = 30;
  std::vector<Pose2> odometry;
  for (std::size_t i = 0; i < n; ++i) odometry.push_back(loop.log.scans[i].odometry);
  const HitCountGrid base(0.05, Eigen::Vector2d(-2, -2), 600, 460);
  GlobalSearchParams params;
  params.set_partitions(3);
  const GlobalSearchProblem problem(loop.log.scans, odometry, 10, n, base, params,
                                    PartitionErrorBounds(params), std::nullopt);
  EXPECT_EQ(problem.lower().size(), 18);
  const std::vector<Pose2> same = problem.Apply(problem.Identity());
  ASSERT_EQ(same.size(), n - 10);
  for (std::size_t k = 0; k < same.size(); ++k) {
    EXPECT_NEAR((same[k].translation() - odometry[10 + k].translation()).norm(), 0.0, 1e-9);
  }
  // A heading error in the first partition turns everything after it by exactly that much.
  Eigen::VectorXd x = problem.Identity();
  x(4) = 0.1;
  const std::vector<Pose2> turned = problem.Apply(x);
  EXPECT_NEAR(WrapAngle(turned.back().theta() - odometry.back().theta()), 0.1, 1e-9);
  EXPECT_THROW(GlobalSearchProblem(loop.log.scans, odometry, 10, n + 1, base, params,
                                   PartitionErrorBounds(params), std::nullopt),
               Error);
}

// Eqs. 5 to 7 as the paper writes them, nothing spared: each step's weights summed afresh, every
// end point placed with Pose2, the cells sorted to count them. The problem must give these bits.
struct Scored {
  std::vector<Pose2> poses;  // scans [first, last) corrected
  double fitness[2] = {0.0, 0.0};
  std::size_t outside = 0;  // end points off the grid
  // Poses on a cell the base map holds, and on one only the stretch's own end points fill.
  std::size_t on_base = 0, on_own = 0;
};

Scored ScoreAsWritten(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                      std::size_t first, std::size_t last, const HitCountGrid& base,
                      const GlobalSearchParams& params, const std::optional<LoopConstraint>& loop,
                      const Eigen::VectorXd& x) {
  Scored r;
  const std::size_t begin = std::max<std::size_t>(first, 1), steps = last - begin;
  const std::size_t partitions =
      std::max<std::size_t>(1, std::min<std::size_t>(params.partitions(), steps));
  if (first < begin) r.poses.push_back(poses[0]);
  Pose2 pose = poses[begin - 1];
  for (std::size_t i = 0; i < partitions; ++i) {
    const std::size_t b = i * steps / partitions, e = (i + 1) * steps / partitions;
    for (std::size_t j = b; j < e; ++j) {
      double error[3];
      for (int axis = 0; axis < 3; ++axis) {
        const auto weight = [&](std::size_t k) {
          const double t = (static_cast<double>(k - b) + 0.5) / static_cast<double>(e - b);
          const double d = (t - x(static_cast<Eigen::Index>(6 * i + 2 * axis + 1))) /
                           GaussianWidths(params)(axis);
          return std::exp(-0.5 * d * d);
        };
        double sum = 0.0;
        for (std::size_t k = b; k < e; ++k) sum += weight(k);
        const double delta = x(static_cast<Eigen::Index>(6 * i + 2 * axis));
        error[axis] = sum > 0 ? delta * weight(j) / sum : 0.0;
      }
      const Pose2 step = poses[begin + j - 1].inverse() * poses[begin + j];
      pose = pose * (step * Pose2(error[0], error[1], error[2]));
      r.poses.push_back(pose);
    }
  }
  std::vector<Eigen::Vector2d> points;
  const std::size_t n = last - first;
  const std::size_t scan_stride =
      params.scored_scans() > 0
          ? std::max<std::size_t>(1, (n + params.scored_scans() - 1) / params.scored_scans())
          : 1;
  for (std::size_t k = 0; k < r.poses.size(); k += scan_stride) {
    const std::vector<Eigen::Vector2d> returns = ReturnPoints(scans[first + k]);
    for (std::size_t i = 0; i < returns.size(); i += params.beam_stride()) {
      points.push_back(r.poses[k] * returns[i]);
    }
  }
  const testing::CountedInsertion added = testing::CountAsWritten(base, points);
  r.outside = points.size() - added.inside;
  const double occupied = static_cast<double>(base.occupied() + added.fresh);
  r.fitness[0] = occupied > 0 ? -static_cast<double>(base.total() + added.inside) / occupied : 0.0;
  for (const Pose2& p : r.poses) {
    const auto c = base.CellIndex(p.translation());
    if (!c) continue;
    if (base.count(*c) > 0) {
      ++r.on_base;
    } else {
      r.on_own += std::binary_search(added.cells.begin(), added.cells.end(), *c);
    }
  }
  const double conflicts = static_cast<double>(r.on_base + r.on_own);
  double distance = 0.0;
  if (loop) {
    const Pose2 earlier =
        loop->earlier < first ? poses[loop->earlier] : r.poses[loop->earlier - first];
    const Eigen::Vector2d miss =
        r.poses[loop->later - first].translation() - (earlier * loop->relative).translation();
    const double along = miss.norm();
    const std::vector<Eigen::Vector2d> returns = ReturnPoints(scans[loop->later]);
    double squares = 0.0;
    for (const Eigen::Vector2d& p : returns) squares += p.squaredNorm();
    const double lever = std::sqrt(squares / static_cast<double>(returns.size()));
    const double turn =
        WrapAngle(r.poses[loop->later - first].theta() - (earlier * loop->relative).theta());
    distance = std::hypot(along, lever * turn);
  }
  r.fitness[1] = params.occupied_pose_weight() * conflicts + params.loop_miss_weight() * distance;
  return r;
}

TEST(GlobalSearchProblemTest, ScoresRandomCandidatesToTheBitAsTheEquationsAreWritten) {
  SimulationOptions sim;
  sim.laser.beams = 61;
  sim.max_scans = 70;
  const Dataset log = Simulate(BuiltinWorld("office-cluster"), sim);
  std::vector<Pose2> odometry;
  for (const LaserScan& s : log.scans) odometry.push_back(s.odometry);
  // Cut short of the world, so that some end points fall off the grid.
  HitCountGrid base(0.05, Eigen::Vector2d(-2, -2), 400, 460);
  const Pose2 nudge(0.2, -0.1, 0.05);
  struct Case {
    std::size_t first, last;
    LoopConstraint loop;
    std::size_t beam_stride;
    std::size_t scored_scans;  // 7 and 13 of 40: eq. 6 re-inserts one scan in 6, in 4
  };
  for (const Case& c :
       {Case{0, 40, {5, 35, odometry[5].inverse() * odometry[35] * nudge}, 1, 0},
        Case{30, 70, {10, 60, odometry[10].inverse() * odometry[60] * nudge}, 2, 0},
        Case{30, 70, {40, 65, odometry[40].inverse() * odometry[65] * nudge}, 3, 0},
        Case{0, 40, {5, 35, odometry[5].inverse() * odometry[35] * nudge}, 1, 7},
        Case{30, 70, {10, 60, odometry[10].inverse() * odometry[60] * nudge}, 2, 13}}) {
    HitCountGrid others = base;
    for (std::size_t i = 0; i < log.scans.size(); ++i) {
      if (i < c.first || i >= c.last) others.AddScan(log.scans[i], odometry[i]);
    }
    GlobalSearchParams params;
    params.set_partitions(6);
    params.set_beam_stride(c.beam_stride);
    params.set_scored_scans(c.scored_scans);
    const GlobalSearchProblem problem(log.scans, std::span(odometry).first(c.last), c.first, c.last,
                                      others, params, PartitionErrorBounds(params), c.loop);
    Rng rng(c.first + c.loop.earlier);
    constexpr Eigen::Index kCandidates = 40;
    Eigen::MatrixXd batch(problem.lower().size(), kCandidates);
    for (Eigen::Index i = 0; i < kCandidates; ++i) {
      for (Eigen::Index g = 0; g < batch.rows(); ++g) {
        batch(g, i) = rng.Uniform(problem.lower()(g), problem.upper()(g));
      }
    }
    batch.col(0) = problem.Identity();
    std::vector<double> fitness(2 * kCandidates);
    problem.Evaluate(batch, fitness);
    std::size_t outside = 0, on_base = 0, on_own = 0;
    for (Eigen::Index i = 0; i < kCandidates; ++i) {
      const Scored want = ScoreAsWritten(log.scans, odometry, c.first, c.last, others, params,
                                         c.loop, batch.col(i));
      EXPECT_EQ(problem.Apply(batch.col(i)), want.poses) << "candidate " << i;
      EXPECT_EQ(fitness[2 * i], want.fitness[0]) << "candidate " << i;
      EXPECT_EQ(fitness[2 * i + 1], want.fitness[1]) << "candidate " << i;
      outside += want.outside;
      on_base += want.on_base;
      on_own += want.on_own;
    }
    // The cases the scores branch on were met.
    EXPECT_GT(outside, 0u);
    EXPECT_GT(on_base, 0u);
    EXPECT_GT(on_own, 0u);
  }
}

}  // namespace
}  // namespace evoslam

namespace evoslam {
namespace {

// Thirty scans of the office cluster at their odometry poses, and a map with nothing on it, so
// that eq. 7 of a stretch holds its loop term alone (with w1 = 0).
struct LoopScene {
  Dataset log;
  std::vector<Pose2> poses;
  HitCountGrid empty{0.05, Eigen::Vector2d(-2, -2), 600, 460};

  // Eq. 7 of the stretch [10, 30) as it stands, with its loop terms alone at weight 1.
  double LoopTerm(const LoopConstraint& loop) const {
    GlobalSearchParams params;
    params.set_occupied_pose_weight(0.0);
    params.set_loop_miss_weight(1.0);
    const GlobalSearchProblem problem(log.scans, poses, 10, 30, empty, params,
                                      PartitionErrorBounds(params), loop);
    std::vector<double> fitness(2);
    problem.Evaluate(problem.Identity(), fitness);
    return fitness[1];
  }
};

LoopScene MakeLoopScene() {
  SimulationOptions sim;
  sim.laser.beams = 31;
  sim.max_scans = 30;
  LoopScene scene{Simulate(BuiltinWorld("office-cluster"), sim), {}};
  for (const LaserScan& s : scene.log.scans) scene.poses.push_back(s.odometry);
  return scene;
}

// A loop closed in place but not in heading leaves the later scan's walls turned: eq. 7 counts
// the turn by how far it moves the scan's returns, their RMS range times the angle.
TEST(GlobalSearchProblemTest, AHeadingMissCountsByHowFarItTurnsTheLaterScansReturns) {
  const LoopScene scene = MakeLoopScene();
  const std::vector<Pose2>& poses = scene.poses;
  double squares = 0.0;
  const std::vector<Eigen::Vector2d> returns = ReturnPoints(scene.log.scans[25]);
  ASSERT_FALSE(returns.empty());
  for (const Eigen::Vector2d& p : returns) squares += p.squaredNorm();
  const double rms = std::sqrt(squares / static_cast<double>(returns.size()));
  for (const double turn : {0.1, -0.05}) {
    const LoopConstraint loop{
        5, 25, poses[5].inverse() * Pose2(poses[25].translation(), poses[25].theta() + turn)};
    EXPECT_NEAR(scene.LoopTerm(loop), rms * std::abs(turn), 1e-9) << turn;
  }
}

// The start that closes a loop: the later pose lands where the match puts it, heading and
// position, as long as the bounds allow; tighter bounds leave it part-way, never outside them.
TEST(GlobalSearchProblemTest, TheClosingCandidateClosesTheLoopWithinTheBounds) {
  const LoopScene scene = MakeLoopScene();
  const Dataset& log = scene.log;
  const std::vector<Pose2>& poses = scene.poses;
  const HitCountGrid& empty = scene.empty;
  const LoopConstraint loop{5, 25, poses[5].inverse() * poses[25] * Pose2(0.3, -0.2, 0.05)};
  const Pose2 want = poses[5] * loop.relative;
  GlobalSearchParams params;
  const auto miss = [&](const GlobalSearchProblem& problem, const Eigen::VectorXd& x) {
    return want.inverse() * problem.Apply(x)[25 - 10];
  };

  // The loop ending the stretch, as RunRssSlam's do, and ending inside it.
  for (const std::size_t last : {26u, 30u}) {
    const GlobalSearchProblem problem(log.scans, std::span(poses).first(last), 10, last, empty,
                                      params, PartitionErrorBounds(params), loop);
    const std::optional<Eigen::VectorXd> closing = problem.ClosingCandidate();
    ASSERT_TRUE(closing) << last;
    EXPECT_NEAR(miss(problem, *closing).translation().norm(), 0.0, 1e-9) << last;
    EXPECT_NEAR(miss(problem, *closing).theta(), 0.0, 1e-9) << last;
    const std::vector<Eigen::VectorXd> starts = problem.starts();
    ASSERT_EQ(starts.size(), 2u);
    EXPECT_EQ(starts[0], problem.Identity());
    EXPECT_EQ(starts[1], *closing);
  }

  const GlobalSearchProblem tight(log.scans, poses, 10, 30, empty, params,
                                  Eigen::Vector3d(0.01, 0.01, 0.002), loop);
  const Eigen::VectorXd part_way = *tight.ClosingCandidate();
  EXPECT_TRUE((part_way.array() >= tight.lower().array()).all());
  EXPECT_TRUE((part_way.array() <= tight.upper().array()).all());
  const Pose2 left = miss(tight, part_way), open = miss(tight, tight.Identity());
  EXPECT_LT(std::abs(left.theta()), std::abs(open.theta()) - 0.01);
  EXPECT_GT(std::abs(left.theta()), 0.01);

  EXPECT_FALSE(GlobalSearchProblem(log.scans, poses, 10, 30, empty, params,
                                   PartitionErrorBounds(params), std::nullopt)
                   .ClosingCandidate());
  EXPECT_EQ(GlobalSearchProblem(log.scans, poses, 10, 30, empty, params,
                                PartitionErrorBounds(params), std::nullopt)
                .starts()
                .size(),
            1u);
  // A loop that starts inside the stretch would bend with it.
  EXPECT_FALSE(GlobalSearchProblem(log.scans, poses, 3, 30, empty, params,
                                   PartitionErrorBounds(params), loop)
                   .ClosingCandidate());
}

TEST(PickGlobalSolutionTest, LowestSecondObjectiveOfTheFirstFrontWithinTheBound) {
  Eigen::MatrixXd f(2, 5);
  // Columns: (map score, loop and path score), both minimised.
  f << -30, -29, -25, -31, -29,  //
      0.50, 0.10, 0.00, 0.80, 0.10;
  EXPECT_EQ(PickGlobalSolution(f), 2u);  // the loop closed best
  // Within 2 % of -30 only columns 0 and 3 compete.
  EXPECT_EQ(PickGlobalSolution(f, -30 + 0.6), 0u);
  f(0, 4) = -29.5;  // now 4 competes too, and closes the loop better
  EXPECT_EQ(PickGlobalSolution(f, -30 + 0.6), 4u);
  f(0, 1) = -29.5;  // 1 and 4 tie on both: the first wins
  EXPECT_EQ(PickGlobalSolution(f, -30 + 0.6), 1u);
  f(0, 4) = -29.8;  // the sharper of a tie on the second wins
  EXPECT_EQ(PickGlobalSolution(f, -30 + 0.6), 4u);
  EXPECT_EQ(PickGlobalSolution(f, -40), std::nullopt);
  EXPECT_EQ(PickGlobalSolution(Eigen::MatrixXd(2, 0)), std::nullopt);
}

TEST(WorthApplyingTest, ACorrectionThatClosesTheLoopBetterIsWorthIt) {
  const double before[2] = {-37.34, 0.897};
  const double closer[2] = {-37.26, 0.894};  // the map blurred, the loop closed a little better
  EXPECT_TRUE(WorthApplying(before, closer, 0.0));
  const double sharper[2] = {-37.40, 0.897};  // a sharper map is worth it whatever eq. 7 does
  EXPECT_TRUE(WorthApplying(before, sharper, 0.0));
  EXPECT_FALSE(WorthApplying(before, before, 0.0));  // leaving the stretch alone is as good
}

TEST(WorthApplyingTest, ASharperMapMustBeSharperByTheMinimumGain) {
  // A search without a loop on the simulated office cluster: 0.18 % sharper, the trajectory
  // centimetres worse.
  const double before[2] = {-16.0856, 0.0};
  const double slightly[2] = {-16.1152, 0.0};
  EXPECT_TRUE(WorthApplying(before, slightly, 0.0));
  EXPECT_FALSE(WorthApplying(before, slightly, 0.01));
  const double much[2] = {-16.4, 0.0};  // 2 % sharper
  EXPECT_TRUE(WorthApplying(before, much, 0.01));
  const double freed[2] = {-16.0856, -1.0};  // the path crosses fewer obstacles
  EXPECT_TRUE(WorthApplying(before, freed, 0.01));
}

}  // namespace
}  // namespace evoslam
