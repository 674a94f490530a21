#include "worker/task_executor.h"

#include <algorithm>
#include <new>
#include <string>

#include "common/engine/engine_proto.h"
#include "common/engine/island.h"
#include "common/localization/localizer.h"
#include "common/service/job_inputs.h"
#include "common/slam/methods/slam_methods.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kInputsKept = 4;

// A job's log, and its map and the map's image when it has them (a SLAM job builds its map).
std::vector<proto::DatasetRef> DatasetsOf(const proto::ProblemSpec& problem) {
  std::vector<proto::DatasetRef> refs = {problem.log()};
  for (const proto::DatasetRef* ref : {&problem.map(), &problem.map_image()}) {
    if (!ref->sha256().empty()) refs.push_back(*ref);
  }
  return refs;
}

proto::TaskResult Failure(const std::string& task_id, const std::string& message) {
  proto::TaskResult r;
  r.set_task_id(task_id);
  r.mutable_error()->set_code(proto::ERROR_CODE_INVALID);
  r.mutable_error()->set_message(message);
  return r;
}

// A localization job's inputs are named by its datasets' hashes and its parameters.
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

std::shared_ptr<const Problem> TaskExecutor::ProblemOf(const proto::Task& task) {
  const proto::ProblemSpec& spec = task.problem();
  if (spec.kind() == proto::JOB_KIND_LOCALIZE && spec.has_localize()) {
    return LocalizeProblem(task);
  }
  if (spec.kind() == proto::JOB_KIND_SLAM && spec.has_slam()) {
    return SlamProblem(task);
  }
  throw Error("task " + task.task_id() + ": a problem of kind " + std::to_string(spec.kind()) +
              " with " +
              (spec.has_localize() ? "localization"
               : spec.has_slam()   ? "SLAM"
                                   : "no") +
              " parameters is not one this worker knows");
}

std::shared_ptr<const Problem> TaskExecutor::LocalizeProblem(const proto::Task& task) {
  const proto::ProblemSpec& spec = task.problem();
  const std::string inputs_key = InputsKey(spec);
  auto inputs = Lookup(inputs_, inputs_key);
  if (!inputs) {
    inputs = LoadLocalizeInputs(*files_, spec.log(), spec.map(), spec.map_image(), spec.localize());
    Remember(inputs_, inputs_key, inputs);
  }
  if (spec.scan() >= inputs->dataset.scans.size() || spec.center_size() != 3) {
    throw Error("task " + task.task_id() + ": scan " + std::to_string(spec.scan()) +
                " with a centre of " + std::to_string(spec.center_size()) +
                " values does not fit a log of " + std::to_string(inputs->dataset.scans.size()) +
                " scans");
  }
  std::string key = inputs_key + "/" + std::to_string(spec.scan());
  for (double c : spec.center()) key.append(reinterpret_cast<const char*>(&c), sizeof c);
  if (auto hit = Lookup(problems_, key)) return hit;
  auto scan_problem = std::make_shared<const ScanProblem>(
      MakeScanProblem(inputs->map, inputs->dataset, spec.scan(),
                      Pose2(spec.center(0), spec.center(1), spec.center(2)), inputs->options));
  // Shares ownership of the whole scan problem (its renderer included).
  std::shared_ptr<const Problem> problem(scan_problem, scan_problem->problem.get());
  Remember(problems_, std::move(key), problem);
  return problem;
}

std::shared_ptr<const Problem> TaskExecutor::SlamProblem(const proto::Task& task) {
  const proto::ProblemSpec& spec = task.problem();
  // One global search's tasks (every island, every epoch) carry the same spec, and a job runs one
  // search at a time: its next search's problem replaces the last, dropped before the new one is
  // built so that their base maps, each as large as the job's map, are never held together.
  std::string key = spec.SerializeAsString();
  const auto held =
      std::find_if(slam_problems_.begin(), slam_problems_.end(),
                   [&](const SlamProblemHeld& p) { return p.job_id == task.job_id(); });
  if (held != slam_problems_.end()) {
    if (held->key == key) {
      slam_problems_.splice(slam_problems_.begin(), slam_problems_, held);
      return held->problem;
    }
    slam_problems_.erase(held);
  }
  const std::string log_key = spec.log().sha256() + (spec.slam().lenient() ? "/lenient" : "");
  auto log = Lookup(logs_, log_key);
  if (!log) {
    log = LoadSharedJobLog(*files_, spec.log(), spec.slam().lenient());
    Remember(logs_, log_key, log);
  }
  std::shared_ptr<const Problem> problem;
  try {
    problem = FindSlamMethod(spec.slam().method()).TaskProblem(*log, spec);
  } catch (const Error& e) {
    throw Error("task " + task.task_id() + ": " + e.what());
  }
  slam_problems_.push_front({task.job_id(), std::move(key), problem});
  if (slam_problems_.size() > kInputsKept) slam_problems_.pop_back();
  return problem;
}

proto::TaskResult TaskExecutor::Run(const proto::Task& task) {
  try {
    const std::shared_ptr<const Problem> shared = ProblemOf(task);
    const Problem& problem = *shared;
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
  } catch (const std::bad_alloc&) {
    // This worker's memory, not the task: another worker may have enough.
    proto::TaskResult r = Failure(task.task_id(), "out of memory");
    r.set_worker_fault(true);
    return r;
  } catch (const std::exception& e) {
    return Failure(task.task_id(), e.what());
  }
}

}  // namespace evoslam
