#include "coordinator/task_board.h"

#include <algorithm>
#include <utility>

#include "coordinator/result_check.h"

namespace evoslam {

TaskBoard::TaskBoard(std::function<void()> wake, int max_attempts)
    : wake_(std::move(wake)), max_attempts_(max_attempts) {}

std::vector<proto::TaskResult> TaskBoard::RunAll(const std::string& job_id,
                                                 std::vector<proto::Task> tasks) {
  std::vector<std::string> ids;
  {
    std::lock_guard lock(mutex_);
    ThrowIfInterruptedLocked(job_id);
    for (proto::Task& task : tasks) {
      std::string id = "t-" + std::to_string(next_id_++);
      task.set_task_id(id);
      task.set_job_id(job_id);
      line_.push_back(id);
      posted_.emplace(id, Entry{std::move(task), std::nullopt});
      ids.push_back(std::move(id));
    }
  }
  if (wake_) wake_();
  std::unique_lock lock(mutex_);
  const auto forget = [&] {
    for (const auto& id : ids) posted_.erase(id);
    std::erase_if(line_, [&](const std::string& id) { return !posted_.contains(id); });
  };
  done_.wait(lock, [&] {
    return shutdown_ || cancelled_.contains(job_id) ||
           std::all_of(ids.begin(), ids.end(),
                       [&](const std::string& id) { return posted_.at(id).result.has_value(); });
  });
  if (shutdown_ || cancelled_.contains(job_id)) {
    forget();
    ThrowIfInterruptedLocked(job_id);
  }
  std::vector<proto::TaskResult> results;
  results.reserve(ids.size());
  for (const auto& id : ids) results.push_back(std::move(*posted_.at(id).result));
  forget();
  for (const proto::TaskResult& r : results) {
    if (r.has_error()) throw Error("a worker could not run a task: " + r.error().message());
  }
  return results;
}

void TaskBoard::ThrowIfInterrupted(const std::string& job_id) const {
  std::lock_guard lock(mutex_);
  ThrowIfInterruptedLocked(job_id);
}

void TaskBoard::ThrowIfInterruptedLocked(const std::string& job_id) const {
  if (shutdown_) throw JobInterrupted("the coordinator is shutting down");
  if (cancelled_.contains(job_id)) throw JobInterrupted("job " + job_id + " was cancelled");
}

std::optional<proto::Task> TaskBoard::Take() {
  std::lock_guard lock(mutex_);
  while (!line_.empty()) {
    const std::string id = std::move(line_.front());
    line_.pop_front();
    const auto it = posted_.find(id);
    if (it != posted_.end() && !it->second.result) return it->second.task;
  }
  return std::nullopt;
}

bool TaskBoard::Complete(const proto::TaskResult& result) {
  {
    std::lock_guard lock(mutex_);
    const auto it = posted_.find(result.task_id());
    if (it == posted_.end() || it->second.result) return false;
    it->second.result = result;
  }
  done_.notify_all();
  return true;
}

std::optional<std::string> TaskBoard::Check(const proto::TaskResult& result) const {
  std::lock_guard lock(mutex_);
  const auto it = posted_.find(result.task_id());
  if (it == posted_.end() || it->second.result) return std::nullopt;
  return CheckResult(it->second.task, result);
}

void TaskBoard::Return(const std::string& task_id) {
  std::lock_guard lock(mutex_);
  const auto it = posted_.find(task_id);
  if (it == posted_.end() || it->second.result) return;
  if (std::find(line_.begin(), line_.end(), task_id) == line_.end()) line_.push_front(task_id);
}

void TaskBoard::Requeue(const std::string& task_id) {
  {
    std::lock_guard lock(mutex_);
    const auto it = posted_.find(task_id);
    if (it == posted_.end() || it->second.result) return;
    if (++it->second.attempts <= max_attempts_) {
      line_.push_front(task_id);
      return;
    }
    proto::TaskResult failed;
    failed.set_task_id(task_id);
    failed.mutable_error()->set_code(proto::ERROR_CODE_INTERNAL);
    failed.mutable_error()->set_message("task " + task_id + " lost its worker " +
                                        std::to_string(max_attempts_) + " times; giving up");
    it->second.result = std::move(failed);
  }
  done_.notify_all();
}

void TaskBoard::Cancel(const std::string& job_id) {
  {
    std::lock_guard lock(mutex_);
    cancelled_.insert(job_id);
  }
  done_.notify_all();
}

void TaskBoard::Shutdown() {
  {
    std::lock_guard lock(mutex_);
    shutdown_ = true;
  }
  done_.notify_all();
}

std::size_t TaskBoard::waiting() const {
  std::lock_guard lock(mutex_);
  return line_.size();
}

}  // namespace evoslam
