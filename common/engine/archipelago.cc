#include "common/engine/archipelago.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "common/util/error.h"

namespace evoslam {
namespace {

// Stream numbers below the island count belong to the islands.
constexpr std::uint64_t kMigrationStream = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint64_t kAsyncMigrationStream = kMigrationStream - 1;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Runs body(i) for every island on `threads` threads; the first exception is rethrown after all
// islands are done, so none is left half-way.
template <typename Body>
void ForEachIsland(std::size_t islands, std::size_t threads, Body body) {
  std::vector<std::exception_ptr> errors(islands);
  const auto n = static_cast<long>(islands);
#pragma omp parallel for schedule(dynamic, 1) num_threads(static_cast <int>(threads))
  for (long i = 0; i < n; ++i) {
    try {
      body(static_cast<std::size_t>(i));
    } catch (...) {
      errors[static_cast<std::size_t>(i)] = std::current_exception();
    }
  }
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

double BestOf(const Island& island) {
  const Eigen::MatrixXd& f = island.algorithm().population().f;
  return f.cols() > 0 ? f.row(0).minCoeff() : std::numeric_limits<double>::infinity();
}

// LowerBest over every island's population.
bool ImproveBest(const std::vector<Island>& islands, std::vector<double>& best) {
  bool improved = false;
  for (const Island& island : islands)
    improved |= LowerBest(island.algorithm().population().f, best);
  return improved;
}

}  // namespace

void ValidateIslandModelParams(const IslandModelParams& params) {
  if (params.islands == 0) throw Error("island model: at least one island is needed");
  if (params.islands > kMaxIslands) {
    throw Error("island model: more than " + std::to_string(kMaxIslands) + " islands");
  }
  ValidateMigrationParams(params.migration, PopulationSize(params.algorithm));
  MakeAlgorithm(params.algorithm);  // validates the algorithm's own parameters
}

StopCriteria IslandStopCriteria(const StopCriteria& global, std::size_t index, std::size_t islands,
                                bool asynchronous) {
  StopCriteria c;
  if (global.max_evaluations > 0) {
    c.max_evaluations = std::max<std::size_t>(
        1, global.max_evaluations / islands + (index < global.max_evaluations % islands ? 1 : 0));
  }
  c.max_generations = global.max_generations;
  c.target = global.target;
  // Synchronous runs judge stagnation and wall time on the whole archipelago at the barrier.
  if (asynchronous) {
    c.stagnation_generations = global.stagnation_generations;
    c.wall_seconds = global.wall_seconds;
  }
  return c;
}

namespace {

std::vector<Island> FreshIslands(const IslandModelParams& params, const StopCriteria& stop,
                                 std::uint64_t seed) {
  const Rng root(seed);
  std::vector<Island> islands;
  islands.reserve(params.islands);
  for (std::size_t i = 0; i < params.islands; ++i) {
    islands.emplace_back(params.algorithm,
                         IslandStopCriteria(stop, i, params.islands, params.asynchronous),
                         root.Stream(i));
  }
  return islands;
}

}  // namespace

Archipelago::Archipelago(const IslandModelParams& params, const StopCriteria& stop,
                         std::uint64_t seed)
    : Archipelago(params, stop, seed, {}) {
  islands_ = FreshIslands(params_, stop_, seed_);
}

Archipelago::Archipelago(const IslandModelParams& params, const StopCriteria& stop,
                         std::uint64_t seed, std::vector<Island> islands)
    : params_(params), stop_(stop), seed_(seed), islands_(std::move(islands)) {
  ValidateIslandModelParams(params_);
  ValidateStopCriteria(stop_);
}

Archipelago Archipelago::FromCheckpoint(const ArchipelagoCheckpoint& checkpoint) {
  if (checkpoint.islands.size() != checkpoint.params.islands) {
    throw Error("archipelago checkpoint holds " + std::to_string(checkpoint.islands.size()) +
                " islands, its settings say " + std::to_string(checkpoint.params.islands));
  }
  std::vector<Island> islands;
  islands.reserve(checkpoint.islands.size());
  for (const IslandCheckpoint& island : checkpoint.islands)
    islands.push_back(Island::FromCheckpoint(island));
  Archipelago a(checkpoint.params, checkpoint.stop, checkpoint.seed, std::move(islands));
  a.epoch_ = checkpoint.epoch;
  a.progress_ = checkpoint.progress;
  a.started_ = true;
  return a;
}

std::size_t Archipelago::Threads() const {
  const std::size_t wanted =
      params_.threads > 0 ? params_.threads : static_cast<std::size_t>(omp_get_max_threads());
  return std::clamp<std::size_t>(wanted, 1, islands_.size());
}

IslandStepper LocalIslandStepper(const Problem& problem, std::size_t threads) {
  return [&problem, threads](std::vector<Island>& islands, bool start, std::size_t generations) {
    const std::size_t wanted =
        threads > 0 ? threads : static_cast<std::size_t>(omp_get_max_threads());
    ForEachIsland(islands.size(), std::clamp<std::size_t>(wanted, 1, islands.size()),
                  [&](std::size_t i) {
                    if (start) islands[i].Start(problem);
                    if (generations > 0) islands[i].Evolve(problem, generations);
                  });
  };
}

void Archipelago::Start(const Problem& problem) { Start(LocalIslandStepper(problem, Threads())); }

void Archipelago::Start(const IslandStepper& step) {
  const auto start = std::chrono::steady_clock::now();
  step(islands_, true, 0);
  epoch_ = 0;
  progress_ = StopProgress{};
  ImproveBest(islands_, progress_.best);
  progress_.elapsed_seconds = Seconds(start);
  started_ = true;
}

std::optional<StopReason> Archipelago::RunEpoch(const Problem& problem) {
  return RunEpoch(LocalIslandStepper(problem, Threads()));
}

std::optional<StopReason> Archipelago::RunEpoch(const IslandStepper& step) {
  if (!started_) throw Error("archipelago: RunEpoch before Start");
  if (const auto done = CheckGlobal(progress_.elapsed_seconds)) return done;
  const auto start = std::chrono::steady_clock::now();
  const double before = progress_.elapsed_seconds;
  step(islands_, false, params_.migration.interval);
  ++epoch_;
  Migrate(epoch_);
  if (ImproveBest(islands_, progress_.best)) {
    progress_.generations_without_improvement = 0;
  } else {
    progress_.generations_without_improvement += params_.migration.interval;
  }
  return CheckGlobal(before + Seconds(start));
}

std::optional<StopReason> Archipelago::CheckGlobal(double elapsed_seconds) {
  progress_.elapsed_seconds = elapsed_seconds;
  if (stop_.target && progress_.best.size() == 1 && progress_.best[0] <= *stop_.target)
    return StopReason::kTarget;
  if (stop_.stagnation_generations > 0 &&
      progress_.generations_without_improvement >= stop_.stagnation_generations)
    return StopReason::kStagnation;
  if (stop_.wall_seconds > 0.0 && elapsed_seconds >= stop_.wall_seconds)
    return StopReason::kWallTime;
  std::optional<StopReason> all;
  for (const Island& island : islands_) {
    if (!island.stopped()) return std::nullopt;
    if (!all) all = island.stopped();
  }
  return all;
}

void Archipelago::Migrate(std::size_t epoch) {
  if (islands_.size() < 2) return;
  Rng rng = Rng(seed_).Stream(kMigrationStream).Stream(epoch);
  const auto sources = MigrationSources(params_.migration.topology, islands_.size(), rng);
  // Every island chooses its emigrants before any arrive, so the order of arrival cannot matter.
  std::vector<Migrants> emigrants;
  emigrants.reserve(islands_.size());
  for (const Island& island : islands_)
    emigrants.push_back(SelectEmigrants(island.algorithm().population(), params_.migration, rng));
  for (std::size_t d = 0; d < islands_.size(); ++d) {
    std::vector<Migrants> parts;
    for (const std::size_t s : sources[d]) parts.push_back(emigrants[s]);
    Immigrate(islands_[d].algorithm(), Concatenate(parts), params_.migration.policy, rng);
  }
}

StopReason Archipelago::Run(const Problem& problem,
                            const std::function<void(const EpochReport&)>& on_epoch) {
  if (!started_) Start(problem);
  if (params_.asynchronous) return RunAsynchronous(problem, on_epoch);
  for (;;) {
    const auto reason = RunEpoch(problem);
    if (on_epoch) on_epoch(Report());
    if (reason) return *reason;
  }
}

StopReason Archipelago::RunAsynchronous(const Problem& problem,
                                        const std::function<void(const EpochReport&)>& on_epoch) {
  const std::size_t n = islands_.size();
  const auto start = std::chrono::steady_clock::now();
  const double before = progress_.elapsed_seconds;
  std::mutex mutex;  // guards inboxes, the per-island figures and epoch_
  std::vector<std::vector<Migrants>> inboxes(n);
  // Each thread touches only its own island; progress is reported from these copies.
  std::vector<std::size_t> evaluations(n);
  std::vector<double> bests(n);
  for (std::size_t i = 0; i < n; ++i) {
    evaluations[i] = islands_[i].algorithm().evaluations();
    bests[i] = BestOf(islands_[i]);
  }
  std::atomic<bool> stop_all{false};
  std::vector<std::exception_ptr> errors(n);
  {
    std::vector<std::jthread> threads;
    threads.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      threads.emplace_back([&, i] {
        try {
          // The islands are the parallelism here; evaluation threads would only compete with them.
          omp_set_num_threads(1);
          Rng rng = Rng(seed_).Stream(kAsyncMigrationStream).Stream(i);
          Island& island = islands_[i];
          while (!stop_all.load()) {
            const auto reason = island.Evolve(problem, params_.migration.interval);
            if (n > 1) {
              const Migrants out =
                  SelectEmigrants(island.algorithm().population(), params_.migration, rng);
              const auto sources = MigrationSources(params_.migration.topology, n, rng);
              std::vector<Migrants> arrived;
              {
                std::lock_guard lock(mutex);
                for (std::size_t d = 0; d < n; ++d) {
                  if (std::find(sources[d].begin(), sources[d].end(), i) != sources[d].end())
                    inboxes[d].push_back(out);
                }
                arrived.swap(inboxes[i]);
              }
              Immigrate(island.algorithm(), Concatenate(arrived), params_.migration.policy, rng);
            }
            {
              std::lock_guard lock(mutex);
              ++epoch_;
              evaluations[i] = island.algorithm().evaluations();
              bests[i] = BestOf(island);
              if (on_epoch) {
                EpochReport report;
                report.epoch = epoch_;
                for (std::size_t k = 0; k < n; ++k) report.evaluations += evaluations[k];
                report.best = *std::min_element(bests.begin(), bests.end());
                on_epoch(report);
              }
            }
            if (reason == StopReason::kTarget || reason == StopReason::kWallTime) stop_all = true;
            if (reason) break;
          }
        } catch (...) {
          errors[i] = std::current_exception();
          stop_all = true;
        }
      });
    }
  }
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  ImproveBest(islands_, progress_.best);
  progress_.elapsed_seconds = before + Seconds(start);
  for (const Island& island : islands_) {
    if (island.stopped() == StopReason::kTarget) return StopReason::kTarget;
  }
  for (const Island& island : islands_) {
    if (island.stopped()) return *island.stopped();
  }
  return StopReason::kWallTime;
}

ArchipelagoCheckpoint Archipelago::Checkpoint() const {
  ArchipelagoCheckpoint c;
  c.params = params_;
  c.stop = stop_;
  c.seed = seed_;
  c.epoch = epoch_;
  c.progress = progress_;
  for (const Island& island : islands_) c.islands.push_back(island.Checkpoint());
  return c;
}

std::size_t Archipelago::evaluations() const {
  std::size_t total = 0;
  for (const Island& island : islands_) total += island.algorithm().evaluations();
  return total;
}

EpochReport Archipelago::Report() const {
  EpochReport r;
  r.epoch = epoch_;
  r.evaluations = evaluations();
  r.best = std::numeric_limits<double>::infinity();
  for (const Island& island : islands_) r.best = std::min(r.best, BestOf(island));
  return r;
}

OptimResult Archipelago::Best() const {
  OptimResult r;
  r.best_fitness = std::numeric_limits<double>::infinity();
  for (const Island& island : islands_) {
    const Algorithm& a = island.algorithm();
    if (a.champion_f().size() > 0 && a.champion_f()(0) < r.best_fitness) {
      r.best_fitness = a.champion_f()(0);
      r.best = a.champion_x();
    }
    r.evaluations += a.evaluations();
    r.generations = std::max(r.generations, a.generation());
  }
  return r;
}

Population Archipelago::Merged() const {
  std::vector<Migrants> parts;
  for (const Island& island : islands_) {
    const Population& p = island.algorithm().population();
    parts.push_back(Migrants{p.x, p.f});
  }
  Migrants all = Concatenate(parts);
  return Population{std::move(all.x), std::move(all.f)};
}

}  // namespace evoslam
