#include "common/engine/island.h"

#include <chrono>
#include <string>

#include "common/optim/evolve.h"
#include "common/util/error.h"

namespace evoslam {

bool IsUnstarted(const AlgorithmState& state) {
  return state.population.size() == 0 && state.generation == 0 && state.evaluations == 0;
}

Island::Island(const AlgorithmSpec& spec, const StopCriteria& stop, Rng rng)
    : spec_(spec), algorithm_(MakeAlgorithm(spec)), tracker_(stop), rng_(rng) {}

Island Island::FromCheckpoint(const IslandCheckpoint& checkpoint) {
  Island island(checkpoint.algorithm, checkpoint.stop, Rng::FromState(checkpoint.rng));
  if (!IsUnstarted(checkpoint.state)) island.algorithm_->Restore(checkpoint.state);
  island.tracker_ = StopTracker(checkpoint.stop, checkpoint.progress);
  island.stopped_ = checkpoint.stopped;
  return island;
}

void Island::Start(const Problem& problem) {
  const auto start = std::chrono::steady_clock::now();
  algorithm_->Initialize(problem, rng_);
  tracker_ = StopTracker(tracker_.criteria());
  tracker_.Update(*algorithm_,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  stopped_ = tracker_.Check(*algorithm_);
}

std::optional<StopReason> Island::Evolve(const Problem& problem, std::size_t generations) {
  // An island restored from a checkpoint may come from another problem: say so, before any
  // operator reads candidates of the wrong length.
  const auto rows = static_cast<std::size_t>(algorithm_->population().x.rows());
  if (rows != 0 && rows != problem.dimension()) {
    throw Error("island: a population of " + std::to_string(rows) +
                " coordinates for a problem of " + std::to_string(problem.dimension()));
  }
  if (!stopped_) stopped_ = Advance(problem, *algorithm_, tracker_, rng_, generations);
  return stopped_;
}

IslandCheckpoint Island::Checkpoint() const {
  return IslandCheckpoint{spec_,        tracker_.criteria(), algorithm_->Save(),
                          rng_.state(), tracker_.progress(), stopped_};
}

}  // namespace evoslam
