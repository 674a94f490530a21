#include "coordinator/job_context.h"

#include "common/engine/engine_proto.h"
#include "common/service/job_state.h"

namespace evoslam {

CheckpointThrottle::CheckpointThrottle(const JobContext& context)
    : context_(context), last_save_(std::chrono::steady_clock::now()) {}

void CheckpointThrottle::Offer(const std::function<std::string()>& serialize) {
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_save_).count() < context_.checkpoint_seconds) return;
  context_.save_checkpoint(serialize());
  last_save_ = now;
}

void ReportProgress(const JobContext& context, std::uint64_t done, std::uint64_t total,
                    std::uint64_t evaluations, const proto::JobStep& step) {
  if (!context.progress) return;
  proto::JobStatus status;
  status.set_phase(std::string(JobKindName(context.spec.kind())));
  status.set_done(done);
  status.set_total(total);
  status.set_evaluations(evaluations);
  if (!step.name().empty()) *status.mutable_step() = step;
  context.progress(status);
}

void EvolveIslandsRemotely(const JobContext& context, const proto::ProblemSpec& problem,
                           std::vector<Island>& islands, bool start, std::size_t generations) {
  std::vector<proto::Task> tasks;
  for (const Island& island : islands) {
    proto::Task task;
    *task.mutable_problem() = problem;
    proto::EvolveIsland& evolve = *task.mutable_evolve();
    *evolve.mutable_island() = ToProto(island.Checkpoint());
    evolve.set_start(start);
    evolve.set_generations(generations);
    tasks.push_back(std::move(task));
  }
  const auto results = context.board->RunAll(context.job_id, std::move(tasks));
  for (std::size_t i = 0; i < islands.size(); ++i) {
    if (!results[i].has_island()) throw Error("a worker answered an island task with no island");
    islands[i] = Island::FromCheckpoint(FromProto(results[i].island().island()));
  }
}

}  // namespace evoslam
