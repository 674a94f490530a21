#include "coordinator/worker_table.h"

#include <algorithm>

namespace evoslam {

bool WorkerTable::Ready(const std::string& identity, const proto::Ready& ready,
                        Clock::time_point now) {
  if (Seen(identity, now)) return false;
  Worker w;
  w.id = "w-" + std::to_string(++next_id_);
  w.hostname = ready.hostname().substr(0, 255);
  w.threads = ready.threads();
  w.last_seen = now;
  workers_.emplace(identity, std::move(w));
  idle_.push_back(identity);
  return true;
}

bool WorkerTable::Seen(const std::string& identity, Clock::time_point now) {
  const auto it = workers_.find(identity);
  if (it == workers_.end()) return false;
  it->second.last_seen = now;
  return true;
}

std::optional<std::string> WorkerTable::Assign(const std::string& task_id,
                                               Clock::time_point deadline) {
  if (idle_.empty()) return std::nullopt;
  std::string identity = std::move(idle_.front());
  idle_.pop_front();
  Worker& w = workers_.at(identity);
  w.task = task_id;
  w.deadline = deadline;
  return identity;
}

std::optional<std::string> WorkerTable::TaskOf(const std::string& identity) const {
  const auto it = workers_.find(identity);
  return it == workers_.end() ? std::nullopt : it->second.task;
}

void WorkerTable::Done(const std::string& identity) {
  const auto it = workers_.find(identity);
  if (it == workers_.end() || !it->second.task) return;
  it->second.task.reset();
  ++it->second.tasks_done;
  idle_.push_back(identity);
}

std::optional<std::string> WorkerTable::Remove(const std::string& identity) {
  const auto it = workers_.find(identity);
  if (it == workers_.end()) return std::nullopt;
  std::optional<std::string> task = std::move(it->second.task);
  workers_.erase(it);
  std::erase(idle_, identity);
  return task;
}

std::vector<std::string> WorkerTable::Lost(Clock::time_point now,
                                           Clock::time_point silent_since) const {
  std::vector<std::string> lost;
  for (const auto& [identity, w] : workers_) {
    if (w.last_seen < silent_since || (w.task && now > w.deadline)) lost.push_back(identity);
  }
  return lost;
}

std::uint32_t WorkerTable::threads() const {
  std::uint32_t total = 0;
  for (const auto& [identity, w] : workers_) total += w.threads;
  return total;
}

std::vector<std::string> WorkerTable::Identities() const {
  std::vector<std::string> ids;
  for (const auto& [identity, w] : workers_) ids.push_back(identity);
  return ids;
}

std::vector<proto::WorkerInfo> WorkerTable::List(Clock::time_point now, double now_unix_s) const {
  std::vector<proto::WorkerInfo> list;
  for (const auto& [identity, w] : workers_) {
    proto::WorkerInfo info;
    info.set_worker_id(w.id);
    info.set_hostname(w.hostname);
    info.set_threads(w.threads);
    info.set_busy(w.task.has_value());
    info.set_last_seen_unix_s(now_unix_s -
                              std::chrono::duration<double>(now - w.last_seen).count());
    info.set_tasks_done(w.tasks_done);
    list.push_back(std::move(info));
  }
  return list;
}

}  // namespace evoslam
