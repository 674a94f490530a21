#include "coordinator/slam_job.h"

#include <optional>

#include "common/report/slam_outputs.h"
#include "common/service/job_inputs.h"
#include "common/service/slam_checkpoint.h"
#include "common/slam/rss_slam.h"
#include "common/slam/slam_params.h"
#include "common/slam/slam_proto.h"

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
  const Dataset dataset = LoadJobLog(*context.files, spec.log(), params.lenient());
  // Read before the search, so that a bad file fails the job at once, not after all its work.
  const std::optional<NamedRelations> relations =
      LoadJobRelations(*context.files, spec.relations(), dataset);
  const std::size_t scans = ScansToMap(dataset, params);

  const auto resume = ResumeState<proto::SlamCheckpoint>(context, RssSlamStateFromProto);
  CheckpointThrottle throttle(context);
  std::uint64_t evaluations = resume ? resume->local_evaluations + resume->global_evaluations : 0;
  RssSlamRuntime runtime;
  runtime.resume = resume ? &*resume : nullptr;
  runtime.global = [&](const GlobalSearchTask& task, const GlobalSearchProblem&) {
    proto::ProblemSpec problem = job;
    *problem.mutable_global_search() = ToProto(task);
    return IslandStepper([&context, problem = std::move(problem)](
                             std::vector<Island>& islands, bool start, std::size_t generations) {
      EvolveIslandsRemotely(context, problem, islands, start, generations);
    });
  };
  runtime.checkpoint = [&](const RssSlamState& state) {
    // The local search runs here, between tasks: a cancel or a shutdown must not wait for the
    // next global search to be noticed.
    context.board->ThrowIfInterrupted(context.job_id);
    evaluations = state.local_evaluations + state.global_evaluations;
    throttle.Offer([&] { return ToProto(state).SerializeAsString(); });
  };
  runtime.progress = [&](const std::string& phase, std::size_t done, std::size_t total) {
    ReportProgress(context, phase, done, total, evaluations);
  };
  // Progress shows where the job stands from the start, a resumed job included.
  ReportProgress(context, "local search", resume ? resume->next_scan : 0, scans, evaluations);
  const RssSlamResult result = RunRssSlam(dataset, params, runtime);

  return SlamOutputs(dataset, params, result, relations, context.worker_threads);
}

}  // namespace evoslam
