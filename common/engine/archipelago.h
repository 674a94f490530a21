#ifndef EVOSLAM_COMMON_ENGINE_ARCHIPELAGO_H_
#define EVOSLAM_COMMON_ENGINE_ARCHIPELAGO_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "common/engine/algorithm_spec.h"
#include "common/engine/island.h"
#include "common/engine/migration.h"
#include "common/optim/stop_criteria.h"

namespace evoslam {

// N islands, each running its own instance of one algorithm, exchanging migrants every
// `migration.interval` generations.
//
// Synchronous (the default): islands evolve one epoch in parallel, then all migrate at a barrier
// in a fixed order with a random stream derived from the seed and the epoch, so the result is the
// same whatever the thread count. Asynchronous: every island runs on its own thread and takes
// whatever migrants have arrived when it reaches the end of an epoch; faster when islands run at
// different speeds, but no longer reproducible.
struct IslandModelParams {
  std::size_t islands = 4;
  AlgorithmSpec algorithm;
  MigrationParams migration;
  bool asynchronous = false;
  std::size_t threads = 0;  // 0: one per island, at most omp_get_max_threads()
};

// The most islands a model may have: beyond them its memory, not its search, grows.
inline constexpr std::size_t kMaxIslands = 4096;

void ValidateIslandModelParams(const IslandModelParams& params);

// The archipelago between two epochs.
struct ArchipelagoCheckpoint {
  IslandModelParams params;
  StopCriteria stop;
  std::uint64_t seed = 0;
  std::size_t epoch = 0;
  std::vector<IslandCheckpoint> islands;
  StopProgress progress;
};

// Progress after an epoch. In asynchronous mode islands finish their epochs independently, and
// `epoch` counts island-epochs.
struct EpochReport {
  std::size_t epoch = 0;
  std::size_t evaluations = 0;
  double best = 0.0;  // lowest first objective over all islands
};

// Evolves a set of islands in place: starts each first when `start`, then runs each for up to
// `generations` generations. The archipelago's own stepper runs them on local threads; the
// service's sends them to workers, and both leave the islands in the same state.
using IslandStepper =
    std::function<void(std::vector<Island>& islands, bool start, std::size_t generations)>;

// Runs the islands on up to `threads` local threads (0: omp_get_max_threads()).
IslandStepper LocalIslandStepper(const Problem& problem, std::size_t threads = 0);

// The stop criteria apply to the archipelago as a whole: the evaluation budget is shared evenly
// among the islands, the generation limit is per island (they advance together), the target is
// met when any island meets it, stagnation counts generations without the best of all islands
// improving.
class Archipelago {
 public:
  Archipelago(const IslandModelParams& params, const StopCriteria& stop, std::uint64_t seed);
  static Archipelago FromCheckpoint(const ArchipelagoCheckpoint& checkpoint);

  void Start(const Problem& problem);
  void Start(const IslandStepper& step);
  // Synchronous mode: one epoch (evolution, then migration). Returns the stop reason when the
  // run is over.
  std::optional<StopReason> RunEpoch(const Problem& problem);
  std::optional<StopReason> RunEpoch(const IslandStepper& step);
  // Start (unless restored or started) and run to the end in the configured mode.
  StopReason Run(const Problem& problem,
                 const std::function<void(const EpochReport&)>& on_epoch = {});

  ArchipelagoCheckpoint Checkpoint() const;

  std::size_t epoch() const { return epoch_; }
  std::size_t evaluations() const;
  const std::vector<Island>& islands() const { return islands_; }
  // The best candidate of all islands (single-objective problems).
  OptimResult Best() const;
  // All islands' populations side by side, island after island.
  Population Merged() const;

 private:
  // Validates the settings and takes the islands as they are.
  Archipelago(const IslandModelParams& params, const StopCriteria& stop, std::uint64_t seed,
              std::vector<Island> islands);

  std::optional<StopReason> CheckGlobal(double elapsed_seconds);
  void Migrate(std::size_t epoch);
  StopReason RunAsynchronous(const Problem& problem,
                             const std::function<void(const EpochReport&)>& on_epoch);
  std::size_t Threads() const;
  EpochReport Report() const;

  IslandModelParams params_;
  StopCriteria stop_;
  std::uint64_t seed_;
  std::vector<Island> islands_;
  std::size_t epoch_ = 0;
  bool started_ = false;
  StopProgress progress_;
};

// The stop criteria island `index` of `islands` runs under.
StopCriteria IslandStopCriteria(const StopCriteria& global, std::size_t index, std::size_t islands,
                                bool asynchronous);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_ENGINE_ARCHIPELAGO_H_
