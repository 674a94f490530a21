#ifndef EVOSLAM_COMMON_OPTIM_STOP_CRITERIA_H_
#define EVOSLAM_COMMON_OPTIM_STOP_CRITERIA_H_

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "common/optim/algorithm.h"

namespace evoslam {

// When a run ends; the first criterion met wins. Zero means "no limit". A generation is never cut
// short, so a run may pass the evaluation budget by less than one generation's batch.
struct StopCriteria {
  std::size_t max_evaluations = 0;
  std::size_t max_generations = 0;
  // Single-objective problems: stop once the best fitness is at or below this value.
  std::optional<double> target;
  // Stop after this many generations in a row without any objective's best value improving.
  std::size_t stagnation_generations = 0;
  double wall_seconds = 0.0;
};

enum class StopReason { kEvaluations, kGenerations, kTarget, kStagnation, kWallTime, kConverged };
std::string_view StopReasonName(StopReason reason);

// Throws Error when nothing would ever stop a run (no budget, generation limit, stagnation or wall
// time) or a value is out of range.
void ValidateStopCriteria(const StopCriteria& criteria);

// What a stop check remembers between generations; part of a checkpoint, so that a restored run
// stops where the uninterrupted one does.
struct StopProgress {
  std::vector<double> best;  // best value of each objective seen so far
  std::size_t generations_without_improvement = 0;
  double elapsed_seconds = 0.0;  // wall time spent before the last checkpoint
};

// Lowers each entry of `best` to the lowest value of the matching row of f (objectives x n);
// when `best` has another length it starts over at +infinity. Returns whether any entry fell or
// `best` started over.
bool LowerBest(const Eigen::MatrixXd& f, std::vector<double>& best);

// Call Update after every generation (and after Initialize), then Check.
class StopTracker {
 public:
  explicit StopTracker(const StopCriteria& criteria, StopProgress progress = {});

  // Records the population's best values; `elapsed_seconds` is the wall time of the run so far.
  void Update(const Algorithm& algorithm, double elapsed_seconds);
  std::optional<StopReason> Check(const Algorithm& algorithm) const;

  const StopProgress& progress() const { return progress_; }
  const StopCriteria& criteria() const { return criteria_; }

 private:
  StopCriteria criteria_;
  StopProgress progress_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_STOP_CRITERIA_H_
