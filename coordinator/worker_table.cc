#include "coordinator/worker_table.h"

#include <algorithm>
#include <utility>

namespace evoslam {

std::vector<std::string> WorkerTable::PenaltyKeys(const std::string& identity, const Worker& w) {
  std::vector<std::string> keys = {"c:" + identity};
  if (!w.instance.empty()) keys.push_back("i:" + w.instance);
  return keys;
}

WorkerTable::Arrival WorkerTable::Ready(const std::string& identity, const proto::Ready& ready,
                                        Clock::time_point now) {
  Arrival arrival;
  if (Seen(identity, now)) return arrival;
  arrival.is_new = true;
  Worker w;
  w.hostname = ready.hostname().substr(0, 255);
  w.threads = ready.threads();
  w.last_seen = now;
  w.instance = ready.instance().substr(0, 64);
  if (!w.instance.empty()) {
    const auto old = std::find_if(workers_.begin(), workers_.end(),
                                  [&](const auto& e) { return e.second.instance == w.instance; });
    if (old != workers_.end()) {
      w.id = old->second.id;
      w.tasks_done = old->second.tasks_done;
      w.faults = old->second.faults;
      arrival.replaced = old->first;  // a copy: Remove erases the key
      arrival.replaced_task = Remove(*arrival.replaced);
    }
  }
  if (w.id.empty()) w.id = "w-" + std::to_string(++next_id_);
  for (const std::string& key : PenaltyKeys(identity, w)) {
    const auto p = penalties_.find(key);
    if (p != penalties_.end() && p->second.until > now) {
      w.quarantined_until = p->second.until;
      w.quarantine_reason = p->second.reason;
    }
  }
  arrival.quarantined = w.quarantined_until.has_value();
  workers_.emplace(identity, std::move(w));
  if (!arrival.quarantined) idle_.push_back(identity);
  return arrival;
}

bool WorkerTable::Seen(const std::string& identity, Clock::time_point now) {
  const auto it = workers_.find(identity);
  if (it == workers_.end()) return false;
  it->second.last_seen = now;
  return true;
}

std::optional<std::string> WorkerTable::Assign(const std::string& task_id, Clock::time_point now,
                                               Clock::time_point deadline) {
  if (idle_.empty()) return std::nullopt;
  std::string identity = std::move(idle_.front());
  idle_.pop_front();
  Worker& w = workers_.at(identity);
  w.task = task_id;
  w.assigned = now;
  w.deadline = deadline;
  return identity;
}

std::optional<std::string> WorkerTable::TaskOf(const std::string& identity) const {
  const auto it = workers_.find(identity);
  return it == workers_.end() ? std::nullopt : it->second.task;
}

std::optional<WorkerTable::Clock::duration> WorkerTable::HeldFor(const std::string& identity,
                                                                 Clock::time_point now) const {
  const auto it = workers_.find(identity);
  if (it == workers_.end() || !it->second.task) return std::nullopt;
  return now - it->second.assigned;
}

void WorkerTable::Done(const std::string& identity) {
  const auto it = workers_.find(identity);
  if (it == workers_.end() || !it->second.task) return;
  it->second.task.reset();
  ++it->second.tasks_done;
  it->second.faults = 0;
  idle_.push_back(identity);
}

int WorkerTable::Failed(const std::string& identity) {
  const auto it = workers_.find(identity);
  if (it == workers_.end() || !it->second.task) return 0;
  it->second.task.reset();
  idle_.push_back(identity);
  return ++it->second.faults;
}

std::optional<std::string> WorkerTable::Quarantine(const std::string& identity,
                                                   Clock::time_point until,
                                                   const std::string& reason) {
  const auto it = workers_.find(identity);
  if (it == workers_.end()) return std::nullopt;
  Worker& w = it->second;
  w.quarantined_until = until;
  w.quarantine_reason = reason;
  w.faults = 0;
  for (const std::string& key : PenaltyKeys(identity, w)) penalties_[key] = {until, reason};
  std::erase(idle_, identity);
  return std::exchange(w.task, std::nullopt);
}

std::vector<std::string> WorkerTable::Release(Clock::time_point now) {
  std::erase_if(penalties_, [&](const auto& p) { return p.second.until <= now; });
  std::vector<std::string> released;
  for (auto& [identity, w] : workers_) {
    if (!w.quarantined_until || *w.quarantined_until > now) continue;
    w.quarantined_until.reset();
    w.quarantine_reason.clear();
    if (!w.task) idle_.push_back(identity);
    released.push_back(identity);
  }
  return released;
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

std::size_t WorkerTable::busy() const {
  return static_cast<std::size_t>(
      std::count_if(workers_.begin(), workers_.end(), [](const auto& e) { return e.second.task; }));
}

std::size_t WorkerTable::quarantined() const {
  return static_cast<std::size_t>(
      std::count_if(workers_.begin(), workers_.end(),
                    [](const auto& e) { return e.second.quarantined_until.has_value(); }));
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
    if (w.quarantined_until) {
      info.set_quarantined_until_unix_s(
          now_unix_s + std::chrono::duration<double>(*w.quarantined_until - now).count());
      info.set_quarantine_reason(w.quarantine_reason);
    }
    list.push_back(std::move(info));
  }
  return list;
}

}  // namespace evoslam
