#include "coordinator/localize_job.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "common/engine/engine_proto.h"
#include "common/io/relations.h"
#include "common/localization/localizer.h"
#include "common/report/localize_outputs.h"
#include "common/service/localize_checkpoint.h"
#include "common/service/localize_inputs.h"

namespace evoslam {
namespace {

// Candidates per evaluation task of an exhaustive search: enough work to hide a round trip.
constexpr Eigen::Index kEvaluateChunk = 512;

proto::Task TaskFor(const proto::ProblemSpec& problem, std::size_t scan, const Pose2& center) {
  proto::Task task;
  *task.mutable_problem() = problem;
  task.mutable_problem()->set_scan(static_cast<std::uint32_t>(scan));
  for (double v : {center.x(), center.y(), center.theta()}) task.mutable_problem()->add_center(v);
  return task;
}

SearchRuntime RemoteSearch(const JobContext& context, const proto::ProblemSpec& problem,
                           std::size_t scan, const Pose2& center) {
  SearchRuntime runtime;
  runtime.step = [&context, problem, scan, center](const Problem&, std::vector<Island>& islands,
                                                   bool start, std::size_t generations) {
    std::vector<proto::Task> tasks;
    for (const Island& island : islands) {
      proto::Task task = TaskFor(problem, scan, center);
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
  };
  runtime.evaluate = [&context, problem, scan, center](
                         const Problem& local, const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                         std::span<double> fitness) {
    std::vector<proto::Task> tasks;
    for (Eigen::Index first = 0; first < candidates.cols(); first += kEvaluateChunk) {
      const Eigen::Index n = std::min(kEvaluateChunk, candidates.cols() - first);
      proto::Task task = TaskFor(problem, scan, center);
      *task.mutable_evaluate()->mutable_candidates() =
          ToProto(Eigen::MatrixXd(candidates.middleCols(first, n)));
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
  const proto::ProblemSpec problem = LocalizeProblemOf(spec);
  const std::size_t total = ScansToLocalize(inputs->dataset, inputs->options);

  std::optional<LocalizeState> resume;
  if (context.resume) {
    proto::LocalizeCheckpoint c;
    if (!c.ParseFromString(*context.resume)) throw Error("the job's checkpoint is unreadable");
    resume = LocalizeStateFromProto(c);
  }

  using Clock = std::chrono::steady_clock;
  Clock::time_point last_save = Clock::now();
  std::uint64_t evaluations = resume ? resume->done.evaluations : 0;
  LocalizeRuntime runtime;
  runtime.resume = resume ? &*resume : nullptr;
  runtime.search = [&](std::size_t scan, const Pose2& center) {
    return RemoteSearch(context, problem, scan, center);
  };
  runtime.checkpoint = [&](const LocalizeState& state) {
    evaluations = state.done.evaluations;
    const Clock::time_point now = Clock::now();
    if (std::chrono::duration<double>(now - last_save).count() < context.checkpoint_seconds) return;
    context.save_checkpoint(ToProto(state).SerializeAsString());
    last_save = now;
  };
  runtime.progress = [&](std::size_t done, std::size_t) {
    proto::JobStatus status;
    status.set_phase("localize");
    status.set_done(done);
    status.set_total(total);
    status.set_evaluations(evaluations);
    if (context.progress) context.progress(status);
  };
  // Progress shows where the job stands from the start, a resumed job included.
  runtime.progress(resume ? resume->next_scan : 0, total);
  LocalizeResult result = Localize(inputs->map, inputs->dataset, inputs->options, runtime);

  std::optional<NamedRelations> relations;
  if (spec.has_relations() && !spec.relations().sha256().empty()) {
    const auto path = context.files->Find(spec.relations());
    if (!path) throw Error("relations " + spec.relations().name() + " are not available");
    relations = NamedRelations{spec.relations().name(), ReadRelations(*path)};
  }
  return LocalizeOutputs(inputs->map, inputs->dataset, spec.localize(), result, relations,
                         context.worker_threads);
}

}  // namespace evoslam
