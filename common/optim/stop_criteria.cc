#include "common/optim/stop_criteria.h"

#include <cmath>
#include <limits>
#include <utility>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {

std::string_view StopReasonName(StopReason reason) {
  switch (reason) {
    case StopReason::kEvaluations:
      return "evaluation budget";
    case StopReason::kGenerations:
      return "generation limit";
    case StopReason::kTarget:
      return "target fitness reached";
    case StopReason::kStagnation:
      return "stagnation";
    case StopReason::kWallTime:
      return "wall time";
    case StopReason::kConverged:
      return "converged";
  }
  return "unknown";
}

void ValidateStopCriteria(const StopCriteria& c) {
  if (c.max_evaluations == 0 && c.max_generations == 0 && c.stagnation_generations == 0 &&
      !(c.wall_seconds > 0.0)) {
    throw Error(
        "stop criteria: set an evaluation budget, a generation limit, a stagnation limit or a "
        "wall time, or the run never ends");
  }
  if (!IsFiniteNonNegative(c.wall_seconds))
    throw Error("stop criteria: wall time must be a finite number of seconds >= 0");
  if (c.target && std::isnan(*c.target)) throw Error("stop criteria: target fitness is NaN");
}

StopTracker::StopTracker(const StopCriteria& criteria, StopProgress progress)
    : criteria_(criteria), progress_(std::move(progress)) {}

bool LowerBest(const Eigen::MatrixXd& f, std::vector<double>& best) {
  bool improved = false;
  if (best.size() != static_cast<std::size_t>(f.rows())) {
    best.assign(static_cast<std::size_t>(f.rows()), std::numeric_limits<double>::infinity());
    improved = true;
  }
  for (Eigen::Index k = 0; k < f.rows() && f.cols() > 0; ++k) {
    const double v = f.row(k).minCoeff();
    if (v < best[static_cast<std::size_t>(k)]) {
      best[static_cast<std::size_t>(k)] = v;
      improved = true;
    }
  }
  return improved;
}

void StopTracker::Update(const Algorithm& algorithm, double elapsed_seconds) {
  progress_.elapsed_seconds = elapsed_seconds;
  const bool improved = LowerBest(algorithm.population().f, progress_.best);
  // The first update only sets the baseline, so it neither counts nor resets a stagnation run.
  if (algorithm.generation() == 0) return;
  progress_.generations_without_improvement =
      improved ? 0 : progress_.generations_without_improvement + 1;
}

std::optional<StopReason> StopTracker::Check(const Algorithm& algorithm) const {
  if (criteria_.target && progress_.best.size() == 1 && progress_.best[0] <= *criteria_.target)
    return StopReason::kTarget;
  if (algorithm.Converged()) return StopReason::kConverged;
  if (criteria_.max_evaluations > 0 && algorithm.evaluations() >= criteria_.max_evaluations)
    return StopReason::kEvaluations;
  if (criteria_.max_generations > 0 && algorithm.generation() >= criteria_.max_generations)
    return StopReason::kGenerations;
  if (criteria_.stagnation_generations > 0 &&
      progress_.generations_without_improvement >= criteria_.stagnation_generations)
    return StopReason::kStagnation;
  if (criteria_.wall_seconds > 0.0 && progress_.elapsed_seconds >= criteria_.wall_seconds)
    return StopReason::kWallTime;
  return std::nullopt;
}

}  // namespace evoslam
