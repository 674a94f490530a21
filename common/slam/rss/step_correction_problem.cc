#include "common/slam/rss/step_correction_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// End points a batch must hold before it is split across threads: a local search generation (10
// candidates of 180 returns, about 10 us) ran 2x slower on two threads than on one with
// OMP_WAIT_POLICY=passive, and 1000x slower with spinning threads, on a shared 2-core machine.
constexpr std::size_t kMinParallelPoints = 1 << 15;

}  // namespace

LocalFitness ParseLocalFitness(std::string_view name) {
  if (name == "eval1") return LocalFitness::kEval1;
  if (name == "eval2") return LocalFitness::kEval2;
  throw Error("unknown local fitness '" + std::string(name) + "' (expected eval1 or eval2)");
}

std::string_view LocalFitnessName(LocalFitness fitness) {
  return fitness == LocalFitness::kEval1 ? "eval1" : "eval2";
}

StepCorrectionProblem::StepCorrectionProblem(const HitCountGrid& map, const LaserScan& scan,
                                             const Pose2& predicted,
                                             const Eigen::Vector3d& max_error, LocalFitness fitness,
                                             double odometry_pull, bool free_frontier)
    : map_(map),
      predicted_(predicted),
      fitness_(fitness),
      free_frontier_(free_frontier),
      lower_(-max_error),
      upper_(max_error) {
  if (!(max_error.array() >= 0.0).all() || !max_error.allFinite()) {
    throw Error("local search: the maximum step error must be finite and not negative");
  }
  if (!IsFiniteNonNegative(odometry_pull)) {
    throw Error("local search: the odometry pull must be finite and not negative");
  }
  returns_ = ReturnPoints(scan);
  double reach = 0.0;
  for (const Eigen::Vector2d& p : returns_) reach = std::max(reach, p.norm());
  // Every candidate's end points lie within this distance of the predicted ones.
  const double margin = max_error.head<2>().norm() + reach * max_error(2) + map.resolution();
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const Eigen::Vector2d& p : returns_) {
    const Eigen::Vector2d w = predicted_ * p;
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  if (!returns_.empty()) {
    const Eigen::Vector2d c0 = (lo.array() - margin - map.origin().array()) / map.resolution();
    const Eigen::Vector2d c1 = (hi.array() + margin - map.origin().array()) / map.resolution();
    const auto clamp = [](double v) { return static_cast<int>(std::clamp(v, -1e9, 1e9)); };
    window_ = map.Window(clamp(std::floor(c0.x())), clamp(std::floor(c0.y())),
                         clamp(std::floor(c1.x())) + 1, clamp(std::floor(c1.y())) + 1);
  }
  if (odometry_pull > 0.0) {
    const double cell = fitness == LocalFitness::kEval1
                            ? 1.0
                            : 1.0 / static_cast<double>(std::max<std::size_t>(1, window_.occupied));
    for (int axis = 0; axis < 3; ++axis) {
      if (max_error(axis) > 0.0)
        pull_(axis) = odometry_pull * cell / (3.0 * max_error(axis) * max_error(axis));
    }
  }
}

Pose2 StepCorrectionProblem::Corrected(const Eigen::Ref<const Eigen::VectorXd>& error) const {
  return predicted_ * Pose2(error(0), error(1), error(2));
}

double StepCorrectionProblem::Score(const Eigen::Ref<const Eigen::VectorXd>& error) const {
  CellSet cells(returns_.size());
  return Score(error, cells);
}

double StepCorrectionProblem::Score(const Eigen::Ref<const Eigen::VectorXd>& error,
                                    CellSet& cells) const {
  cells.Clear();
  HitCountGrid::Insertion added;  // fresh: the cells the scan makes occupied
  map_.CountInsertion(Pose2Frame(Corrected(error)), returns_, cells, added, free_frontier_);
  const double occupied = static_cast<double>(window_.occupied + added.fresh);
  const double pull = pull_.dot(error.head<3>().cwiseAbs2());
  if (fitness_ == LocalFitness::kEval1) return occupied + pull;
  const double total = static_cast<double>(window_.total + added.inside);
  return (occupied > 0 ? -total / occupied : 0.0) + pull;
}

void StepCorrectionProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                                     std::span<double> fitness) const {
  const Eigen::Index n = candidates.cols();
  const bool threaded = static_cast<std::size_t>(n) * returns_.size() >= kMinParallelPoints;
#pragma omp parallel if (threaded)
  {
    CellSet cells(returns_.size());
#pragma omp for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) {
      fitness[static_cast<std::size_t>(i)] = Score(candidates.col(i), cells);
    }
  }
}

}  // namespace evoslam
