#ifndef EVOSLAM_COMMON_ENGINE_ISLAND_H_
#define EVOSLAM_COMMON_ENGINE_ISLAND_H_

#include <cstddef>
#include <memory>
#include <optional>

#include "common/engine/algorithm_spec.h"
#include "common/optim/stop_criteria.h"
#include "common/util/random.h"

namespace evoslam {

// An island frozen between generations: enough to continue it bit for bit in another process.
struct IslandCheckpoint {
  AlgorithmSpec algorithm;
  StopCriteria stop;
  AlgorithmState state;
  RngState rng;
  StopProgress progress;
  std::optional<StopReason> stopped;
};

// True for the state of an algorithm saved before its first population was drawn: nothing to
// restore. The service ships islands to workers before their first generation too.
bool IsUnstarted(const AlgorithmState& state);

// One algorithm instance with its own random stream and stop bookkeeping: the unit that migrates
// between threads and, through the service, between workers.
class Island {
 public:
  // The caller validates `stop`: an archipelago's islands may leave some limits to it.
  Island(const AlgorithmSpec& spec, const StopCriteria& stop, Rng rng);
  static Island FromCheckpoint(const IslandCheckpoint& checkpoint);

  // Draws and evaluates the first population.
  void Start(const Problem& problem);
  // Up to `generations` generations; returns the stop reason once the island is done. Throws
  // Error when its population's candidates do not fit `problem`.
  std::optional<StopReason> Evolve(const Problem& problem, std::size_t generations);

  std::optional<StopReason> stopped() const { return stopped_; }
  const Algorithm& algorithm() const { return *algorithm_; }
  Algorithm& algorithm() { return *algorithm_; }
  const AlgorithmSpec& spec() const { return spec_; }
  const StopTracker& tracker() const { return tracker_; }

  IslandCheckpoint Checkpoint() const;

 private:
  AlgorithmSpec spec_;
  std::unique_ptr<Algorithm> algorithm_;
  StopTracker tracker_;
  Rng rng_;
  std::optional<StopReason> stopped_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_ENGINE_ISLAND_H_
