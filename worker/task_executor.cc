#include "worker/task_executor.h"

#include <string>

#include "common/engine/engine_proto.h"
#include "common/engine/island.h"
#include "common/localization/localizer.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kInputsKept = 4;

std::vector<proto::DatasetRef> DatasetsOf(const proto::ProblemSpec& problem) {
  std::vector<proto::DatasetRef> refs = {problem.log(), problem.map()};
  if (!problem.map_image().sha256().empty()) refs.push_back(problem.map_image());
  return refs;
}

proto::TaskResult Failure(const std::string& task_id, const std::string& message) {
  proto::TaskResult r;
  r.set_task_id(task_id);
  r.mutable_error()->set_code(proto::ERROR_CODE_INVALID);
  r.mutable_error()->set_message(message);
  return r;
}

}  // namespace

TaskExecutor::TaskExecutor(std::shared_ptr<DatasetFiles> files) : files_(std::move(files)) {}

std::vector<proto::DatasetRef> TaskExecutor::Missing(const proto::Task& task) const {
  std::vector<proto::DatasetRef> missing;
  for (const proto::DatasetRef& ref : DatasetsOf(task.problem())) {
    if (!files_->Find(ref)) missing.push_back(ref);
  }
  return missing;
}

std::shared_ptr<const LocalizeInputs> TaskExecutor::Inputs(const proto::ProblemSpec& problem) {
  std::string key;
  for (const proto::DatasetRef& ref : DatasetsOf(problem)) key += ref.sha256() + "/";
  key += problem.localize().SerializeAsString();
  for (auto it = inputs_.begin(); it != inputs_.end(); ++it) {
    if (it->first == key) {
      inputs_.splice(inputs_.begin(), inputs_, it);
      return it->second;
    }
  }
  auto inputs = LoadLocalizeInputs(*files_, problem.log(), problem.map(), problem.map_image(),
                                   problem.localize());
  inputs_.emplace_front(std::move(key), inputs);
  if (inputs_.size() > kInputsKept) inputs_.pop_back();
  return inputs;
}

proto::TaskResult TaskExecutor::Run(const proto::Task& task) {
  try {
    const proto::ProblemSpec& spec = task.problem();
    if (spec.kind() != proto::JOB_KIND_LOCALIZE || !spec.has_localize()) {
      throw Error("task " + task.task_id() + ": a problem of kind " + std::to_string(spec.kind()) +
                  " is not one this worker knows");
    }
    const auto inputs = Inputs(spec);
    if (spec.scan() >= inputs->dataset.scans.size() || spec.center_size() != 3) {
      throw Error("task " + task.task_id() + ": scan " + std::to_string(spec.scan()) +
                  " with a centre of " + std::to_string(spec.center_size()) +
                  " values does not fit a log of " + std::to_string(inputs->dataset.scans.size()) +
                  " scans");
    }
    const ScanProblem scan_problem =
        MakeScanProblem(inputs->map, inputs->dataset, spec.scan(),
                        Pose2(spec.center(0), spec.center(1), spec.center(2)), inputs->options);
    const Problem& problem = *scan_problem.problem;
    proto::TaskResult result;
    result.set_task_id(task.task_id());
    if (task.has_evaluate()) {
      const Eigen::MatrixXd x = FromProto(task.evaluate().candidates(), "candidates");
      if (x.rows() != problem.lower().size()) {
        throw Error("task " + task.task_id() + ": candidates of " + std::to_string(x.rows()) +
                    " coordinates for a problem of " + std::to_string(problem.lower().size()));
      }
      Eigen::MatrixXd f(static_cast<Eigen::Index>(problem.objectives()), x.cols());
      problem.Evaluate(x, std::span<double>(f.data(), static_cast<std::size_t>(f.size())));
      *result.mutable_fitness() = ToProto(f);
    } else if (task.has_evolve()) {
      const proto::EvolveIsland& evolve = task.evolve();
      Island island = Island::FromCheckpoint(FromProto(evolve.island()));
      const Population& population = island.algorithm().population();
      if (!evolve.start() && population.x.rows() != problem.lower().size()) {
        throw Error("task " + task.task_id() + ": an island of " +
                    std::to_string(population.x.rows()) + " coordinates for a problem of " +
                    std::to_string(problem.lower().size()));
      }
      if (evolve.start()) island.Start(problem);
      if (evolve.generations() > 0) island.Evolve(problem, evolve.generations());
      *result.mutable_island()->mutable_island() = ToProto(island.Checkpoint());
    } else {
      throw Error("task " + task.task_id() + " asks for no work");
    }
    return result;
  } catch (const std::exception& e) {
    return Failure(task.task_id(), e.what());
  }
}

}  // namespace evoslam
