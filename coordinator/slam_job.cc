#include "coordinator/slam_job.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <optional>

#include "common/report/slam_outputs.h"
#include "common/service/job_inputs.h"
#include "common/slam/memory_need.h"
#include "common/slam/methods/slam_methods.h"
#include "common/util/available_memory.h"

namespace evoslam {

proto::ProblemSpec SlamProblemOf(const proto::JobSpec& spec) {
  proto::ProblemSpec problem;
  problem.set_kind(proto::JOB_KIND_SLAM);
  *problem.mutable_log() = spec.log();
  *problem.mutable_slam() = CompleteSlamParams(spec.slam());
  return problem;
}

std::vector<proto::ResultFile> RunSlamJob(const JobContext& context) {
  const proto::JobSpec& spec = context.spec;
  const proto::ProblemSpec job = SlamProblemOf(spec);
  const proto::SlamParams& params = job.slam();
  const SlamMethod& method = FindSlamMethod(params.method());
  // Shared with the workers' tasks when they run in this process.
  const std::shared_ptr<const Dataset> log =
      LoadSharedJobLog(*context.files, spec.log(), params.lenient());
  const Dataset& dataset = *log;
  // Read before the search, so that a bad file fails the job at once, not after all its work.
  const std::optional<NamedRelations> relations =
      LoadJobRelations(*context.files, spec.relations(), dataset);

  // Before anything is built: a run that cannot fit is refused rather than killed midway.
  if (const auto warning =
          CheckMemoryNeed(method.PeakMemory(dataset, params), AvailableMemoryBytes())) {
    spdlog::warn("{}", *warning);
  }

  CheckpointThrottle throttle(context);
  SlamHooks hooks;
  if (context.resume) hooks.resume = *context.resume;
  hooks.islands = [&](const proto::ProblemSpec& task) {
    proto::ProblemSpec problem = job;
    problem.MergeFrom(task);
    return IslandStepper([&context, problem = std::move(problem)](
                             std::vector<Island>& islands, bool start, std::size_t generations) {
      EvolveIslandsRemotely(context, problem, islands, start, generations);
    });
  };
  hooks.checkpoint = [&](const std::function<std::string()>& serialize) {
    // The method's own steps run here, between tasks: a cancel or a shutdown must not wait for
    // the next island search to be noticed.
    context.board->ThrowIfInterrupted(context.job_id);
    throttle.Offer(serialize);
  };
  hooks.progress = [&](const SlamProgress& p) {
    proto::JobStep step;
    step.set_name(p.step);
    step.set_done(p.step_done);
    step.set_total(p.step_total);
    ReportProgress(context, p.done, p.total, p.evaluations, step);
  };
  const SlamResult result = method.Run(dataset, params, hooks);
  return SlamOutputs(dataset, params, result, relations, context.worker_threads);
}

}  // namespace evoslam
