#include "coordinator/localize_job.h"

#include <algorithm>
#include <optional>

#include "common/engine/engine_proto.h"
#include "common/localization/localizer.h"
#include "common/report/localize_outputs.h"
#include "common/service/job_inputs.h"
#include "common/service/localize_checkpoint.h"
#include "common/service/localize_inputs.h"

namespace evoslam {
namespace {

// Candidates per evaluation task of an exhaustive search: enough work to hide a round trip.
constexpr Eigen::Index kEvaluateChunk = 512;

proto::ProblemSpec ProblemFor(const proto::ProblemSpec& job, std::size_t scan,
                              const Pose2& center) {
  proto::ProblemSpec problem = job;
  problem.set_scan(static_cast<std::uint32_t>(scan));
  for (double v : {center.x(), center.y(), center.theta()}) problem.add_center(v);
  return problem;
}

SearchRuntime RemoteSearch(const JobContext& context, const proto::ProblemSpec& job,
                           std::size_t scan, const Pose2& center) {
  SearchRuntime runtime;
  runtime.step = [&context, problem = ProblemFor(job, scan, center)](
                     const Problem&, std::vector<Island>& islands, bool start,
                     std::size_t generations) {
    EvolveIslandsRemotely(context, problem, islands, start, generations);
  };
  runtime.evaluate = [&context, problem = ProblemFor(job, scan, center)](
                         const Problem& local, const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                         std::span<double> fitness) {
    std::vector<proto::Task> tasks;
    for (Eigen::Index first = 0; first < candidates.cols(); first += kEvaluateChunk) {
      const Eigen::Index n = std::min(kEvaluateChunk, candidates.cols() - first);
      proto::Task task;
      *task.mutable_problem() = problem;
      *task.mutable_evaluate()->mutable_candidates() =
          ToProto(Eigen::MatrixXd(candidates.middleCols(first, n)));
      task.mutable_evaluate()->set_objectives(static_cast<std::uint32_t>(local.objectives()));
      tasks.push_back(std::move(task));
    }
    const auto results = context.board->RunAll(context.job_id, std::move(tasks));
    std::size_t at = 0;
    for (const proto::TaskResult& r : results) {
      if (!r.has_fitness()) throw Error("a worker answered an evaluation task with no fitness");
      const Eigen::MatrixXd f = FromProto(r.fitness(), "fitness");
      if (f.rows() != static_cast<Eigen::Index>(local.objectives()) ||
          at + static_cast<std::size_t>(f.size()) > fitness.size()) {
        throw Error("a worker answered an evaluation task with a fitness of the wrong shape");
      }
      std::copy(f.data(), f.data() + f.size(), fitness.begin() + static_cast<std::ptrdiff_t>(at));
      at += static_cast<std::size_t>(f.size());
    }
    if (at != fitness.size()) throw Error("workers answered fewer evaluations than were asked");
  };
  return runtime;
}

}  // namespace

proto::ProblemSpec LocalizeProblemOf(const proto::JobSpec& spec) {
  proto::ProblemSpec problem;
  problem.set_kind(spec.kind());
  *problem.mutable_log() = spec.log();
  *problem.mutable_map() = spec.map();
  if (spec.has_map_image()) *problem.mutable_map_image() = spec.map_image();
  *problem.mutable_localize() = spec.localize();
  return problem;
}

std::vector<proto::ResultFile> RunLocalizeJob(const JobContext& context) {
  const proto::JobSpec& spec = context.spec;
  const auto inputs =
      LoadLocalizeInputs(*context.files, spec.log(), spec.map(), spec.map_image(), spec.localize());
  // Read before the search, so that a bad file fails the job at once, not after all its work.
  const std::optional<NamedRelations> relations =
      LoadJobRelations(*context.files, spec.relations(), inputs->dataset);
  const proto::ProblemSpec problem = LocalizeProblemOf(spec);
  const std::size_t total = ScansToLocalize(inputs->dataset, inputs->options);

  const auto resume = ResumeState<proto::LocalizeCheckpoint>(context, LocalizeStateFromProto);
  CheckpointThrottle throttle(context);
  std::uint64_t evaluations = resume ? resume->done.evaluations : 0;
  LocalizeRuntime runtime;
  runtime.resume = resume ? &*resume : nullptr;
  runtime.search = [&](std::size_t scan, const Pose2& center) {
    return RemoteSearch(context, problem, scan, center);
  };
  runtime.checkpoint = [&](const LocalizeState& state) {
    evaluations = state.done.evaluations;
    throttle.Offer([&] { return ToProto(state).SerializeAsString(); });
  };
  runtime.progress = [&](std::size_t done, std::size_t) {
    ReportProgress(context, done, total, evaluations);
  };
  // Progress shows where the job stands from the start, a resumed job included.
  runtime.progress(resume ? resume->next_scan : 0, total);
  LocalizeResult result = Localize(inputs->map, inputs->dataset, inputs->options, runtime);

  return LocalizeOutputs(inputs->map, inputs->dataset, spec.localize(), result, relations,
                         context.worker_threads);
}

}  // namespace evoslam
