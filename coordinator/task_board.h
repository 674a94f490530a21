#ifndef EVOSLAM_COORDINATOR_TASK_BOARD_H_
#define EVOSLAM_COORDINATOR_TASK_BOARD_H_

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/util/error.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Thrown to a job's thread when its job is cancelled, or when the coordinator shuts down.
class JobInterrupted : public Error {
 public:
  using Error::Error;
};

// The tasks job threads post and the broker hands to workers. A job thread posts a set of tasks
// and sleeps until every one has its result; the broker takes waiting tasks one at a time for
// idle workers, completes them, and puts back at the front those whose worker died.
class TaskBoard {
 public:
  // `wake` is called (from the posting thread) whenever tasks start waiting: it wakes the
  // broker. A task whose worker is lost `max_attempts` times fails its job instead of going
  // back once more: a task that kills every worker it reaches must not kill them all.
  explicit TaskBoard(std::function<void()> wake, int max_attempts = 3);

  // Gives every task an id, posts them and waits for their results, in the order of `tasks`.
  // Throws JobInterrupted when the job is cancelled or the board shut down, and Error when a
  // worker reports that a task failed.
  std::vector<proto::TaskResult> RunAll(const std::string& job_id, std::vector<proto::Task> tasks);

  // The oldest waiting task, removed from the waiting line.
  std::optional<proto::Task> Take();
  // What is wrong with `result` as an answer to its task (CheckResult); nullopt when it may be
  // taken, or when nobody waits for it any more (Complete then drops it).
  std::optional<std::string> Check(const proto::TaskResult& result) const;
  // Records a result. False when nobody waits for it any more (a task of a cancelled job, or
  // one already answered): the caller drops it.
  bool Complete(const proto::TaskResult& result);
  // Puts a task that was taken, but whose worker is gone, back at the front of the line, or
  // fails it after max_attempts.
  void Requeue(const std::string& task_id);
  // Puts a task back at the front of the line without counting an attempt: its worker failed
  // through no fault of the task (a send to a closed connection, a stalled coordinator, the
  // worker's own fault or invalid answer).
  void Return(const std::string& task_id);

  // Throws JobInterrupted when the job is cancelled or the board shut down: a job thread that
  // computes between its tasks asks, so that it stops as soon as one waiting for tasks would.
  void ThrowIfInterrupted(const std::string& job_id) const;

  // Wakes the job's waiting thread with JobInterrupted and drops its waiting tasks.
  void Cancel(const std::string& job_id);
  // Interrupts every job; RunAll throws from then on.
  void Shutdown();

  std::size_t waiting() const;

 private:
  struct Entry {
    proto::Task task;
    std::optional<proto::TaskResult> result;
    int attempts = 1;
  };

  void ThrowIfInterruptedLocked(const std::string& job_id) const;  // mutex_ held

  std::function<void()> wake_;
  int max_attempts_;
  mutable std::mutex mutex_;
  std::condition_variable done_;
  std::uint64_t next_id_ = 1;
  std::deque<std::string> line_;         // ids of tasks waiting for a worker
  std::map<std::string, Entry> posted_;  // every task posted and not yet collected
  std::set<std::string> cancelled_;      // jobs whose threads must stop
  bool shutdown_ = false;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_TASK_BOARD_H_
