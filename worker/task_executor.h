#ifndef EVOSLAM_WORKER_TASK_EXECUTOR_H_
#define EVOSLAM_WORKER_TASK_EXECUTOR_H_

#include <list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/optim/problem.h"
#include "common/sensor/dataset.h"
#include "common/service/dataset_files.h"
#include "common/service/localize_inputs.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Runs a coordinator's tasks: rebuilds the task's problem from the job's datasets (the parsed
// inputs of the last few jobs stay in memory) and evaluates a batch or evolves an island on it.
class TaskExecutor {
 public:
  explicit TaskExecutor(std::shared_ptr<DatasetFiles> files);

  // The datasets a task needs that are not in the cache yet.
  std::vector<proto::DatasetRef> Missing(const proto::Task& task) const;
  // Runs a task whose datasets are all here. Never throws: a task that cannot run comes back
  // with an error that says why.
  proto::TaskResult Run(const proto::Task& task);

  // The problems built for tasks and kept for the tasks that repeat them.
  std::size_t problems_held() const { return problems_.size() + slam_problems_.size(); }

 private:
  // Built once for the many tasks of one step (a scan's search, a global search): the task's
  // problem, which owns whatever it refers to.
  std::shared_ptr<const Problem> ProblemOf(const proto::Task& task);
  std::shared_ptr<const Problem> LocalizeProblem(const proto::Task& task);
  std::shared_ptr<const Problem> SlamProblem(const proto::Task& task);

  std::shared_ptr<DatasetFiles> files_;
  // Most recently used first; a handful of jobs at a time is what one worker serves.
  std::list<std::pair<std::string, std::shared_ptr<const LocalizeInputs>>> inputs_;
  std::list<std::pair<std::string, std::shared_ptr<const Dataset>>> logs_;
  std::list<std::pair<std::string, std::shared_ptr<const Problem>>> problems_;
  // A SLAM job's one problem, its current global search's, by job id (most recently used first).
  struct SlamProblemHeld {
    std::string job_id;
    std::string key;
    std::shared_ptr<const Problem> problem;
  };
  std::list<SlamProblemHeld> slam_problems_;
};

}  // namespace evoslam

#endif  // EVOSLAM_WORKER_TASK_EXECUTOR_H_
