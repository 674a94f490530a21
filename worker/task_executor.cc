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

// A job's inputs are named by its datasets' hashes and its parameters.
std::string InputsKey(const proto::ProblemSpec& problem) {
  std::string key;
  for (const proto::DatasetRef& ref : DatasetsOf(problem)) key += ref.sha256() + "/";
  return key + problem.localize().SerializeAsString();
}

// Looks `key` up in a most-recently-used-first list, moving a hit to the front.
template <typename T>
std::shared_ptr<const T> Lookup(std::list<std::pair<std::string, std::shared_ptr<const T>>>& list,
                                const std::string& key) {
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (it->first == key) {
      list.splice(list.begin(), list, it);
      return it->second;
    }
  }
  return nullptr;
}

template <typename T>
void Remember(std::list<std::pair<std::string, std::shared_ptr<const T>>>& list, std::string key,
              std::shared_ptr<const T> value) {
  list.emplace_front(std::move(key), std::move(value));
  if (list.size() > kInputsKept) list.pop_back();
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

std::shared_ptr<const LocalizeInputs> TaskExecutor::Inputs(const proto::ProblemSpec& problem,
                                                           const std::string& key) {
  if (auto hit = Lookup(inputs_, key)) return hit;
  auto inputs = LoadLocalizeInputs(*files_, problem.log(), problem.map(), problem.map_image(),
                                   problem.localize());
  Remember(inputs_, key, inputs);
  return inputs;
}

std::shared_ptr<const ScanProblem> TaskExecutor::ScanProblemOf(const proto::ProblemSpec& spec,
                                                               const LocalizeInputs& inputs,
                                                               const std::string& inputs_key) {
  std::string key = inputs_key + "/" + std::to_string(spec.scan());
  for (double c : spec.center()) key.append(reinterpret_cast<const char*>(&c), sizeof c);
  if (auto hit = Lookup(problems_, key)) return hit;
  auto problem = std::make_shared<const ScanProblem>(
      MakeScanProblem(inputs.map, inputs.dataset, spec.scan(),
                      Pose2(spec.center(0), spec.center(1), spec.center(2)), inputs.options));
  Remember(problems_, std::move(key), problem);
  return problem;
}

proto::TaskResult TaskExecutor::Run(const proto::Task& task) {
  try {
    const proto::ProblemSpec& spec = task.problem();
    if (spec.kind() != proto::JOB_KIND_LOCALIZE || !spec.has_localize()) {
      throw Error("task " + task.task_id() + ": a problem of kind " + std::to_string(spec.kind()) +
                  " is not one this worker knows");
    }
    const std::string key = InputsKey(spec);
    const auto inputs = Inputs(spec, key);
    if (spec.scan() >= inputs->dataset.scans.size() || spec.center_size() != 3) {
      throw Error("task " + task.task_id() + ": scan " + std::to_string(spec.scan()) +
                  " with a centre of " + std::to_string(spec.center_size()) +
                  " values does not fit a log of " + std::to_string(inputs->dataset.scans.size()) +
                  " scans");
    }
    const auto scan_problem = ScanProblemOf(spec, *inputs, key);
    const Problem& problem = *scan_problem->problem;
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
