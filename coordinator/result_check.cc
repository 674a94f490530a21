#include "coordinator/result_check.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "common/engine/engine_proto.h"
#include "common/engine/island.h"

namespace evoslam {
namespace {

bool AllFinite(const proto::Matrix& m) {
  return std::all_of(m.values().begin(), m.values().end(),
                     [](double v) { return std::isfinite(v); });
}

bool WellShaped(const proto::Matrix& m) {
  return static_cast<std::uint64_t>(m.values_size()) ==
         static_cast<std::uint64_t>(m.rows()) * m.cols();
}

std::optional<std::string> CheckFitness(const proto::EvaluateBatch& batch,
                                        const proto::TaskResult& result) {
  if (!result.has_fitness()) return "an answer with no fitness to a batch";
  const proto::Matrix& f = result.fitness();
  if (!WellShaped(f) || f.rows() == 0 || f.cols() != batch.candidates().cols() ||
      (batch.objectives() != 0 && f.rows() != batch.objectives())) {
    return "fitness of " + std::to_string(f.rows()) + "x" + std::to_string(f.cols()) + " for " +
           std::to_string(batch.candidates().cols()) + " candidates";
  }
  if (!AllFinite(f)) return "a fitness that is not finite";
  return std::nullopt;
}

std::optional<std::string> CheckIsland(const proto::EvolveIsland& evolve,
                                       const proto::TaskResult& result) {
  if (!result.has_island()) return "an answer with no island to an island task";
  const proto::IslandCheckpoint& before = evolve.island();
  const proto::IslandCheckpoint& after = result.island().island();
  try {
    // What the job's thread does with it: anything that throws here would fail the job there.
    Island::FromCheckpoint(FromProto(after));
  } catch (const std::exception& e) {
    return std::string("an island that cannot be read: ") + e.what();
  }
  const proto::Matrix& x = after.x();
  const proto::Matrix& f = after.f();
  if (x.rows() == 0 || x.cols() == 0 || f.rows() == 0 || f.cols() != x.cols() ||
      (before.x().rows() != 0 && x.rows() != before.x().rows())) {
    return "an island of " + std::to_string(x.rows()) + "x" + std::to_string(x.cols()) +
           " candidates with " + std::to_string(f.rows()) + "x" + std::to_string(f.cols()) +
           " fitness for one of " + std::to_string(before.x().rows()) + " coordinates";
  }
  if (!AllFinite(x) || !AllFinite(f)) return "an island whose numbers are not all finite";
  // Starting draws the first population afresh: the counts begin again from nothing.
  const std::uint64_t generation = evolve.start() ? 0 : before.generation();
  const std::uint64_t evaluations = evolve.start() ? 0 : before.evaluations();
  const std::uint64_t asked = generation + evolve.generations();
  const bool stopped = !after.stop_reason().empty();
  // An island stops early only by its stop criteria, and then says why.
  if (after.generation() < generation || after.generation() > asked ||
      (!stopped && after.generation() != asked)) {
    return "an island at generation " + std::to_string(after.generation()) + " asked to go from " +
           std::to_string(generation) + " to " + std::to_string(asked);
  }
  const bool advanced = evolve.start() || after.generation() > generation;
  if (after.evaluations() < evaluations || (advanced && after.evaluations() == evaluations)) {
    return "an island of " + std::to_string(after.evaluations()) + " evaluations from one of " +
           std::to_string(evaluations);
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> CheckResult(const proto::Task& task, const proto::TaskResult& result) {
  if (result.task_id() != task.task_id()) {
    return "an answer for " + result.task_id().substr(0, 64) + " to " + task.task_id();
  }
  if (result.has_error()) return std::nullopt;
  if (task.has_evaluate()) return CheckFitness(task.evaluate(), result);
  if (task.has_evolve()) return CheckIsland(task.evolve(), result);
  return std::nullopt;
}

}  // namespace evoslam
