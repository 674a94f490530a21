#ifndef EVOSLAM_COORDINATOR_WORKER_TABLE_H_
#define EVOSLAM_COORDINATOR_WORKER_TABLE_H_

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "evoslam/service.pb.h"

namespace evoslam {

// The workers a coordinator knows, by their socket identity: who is idle (in the order they
// became idle, so work goes to the longest idle first), what each is doing and until when, and
// when each was last heard from.
class WorkerTable {
 public:
  using Clock = std::chrono::steady_clock;

  struct Worker {
    std::string id;  // "w-N": stable while the worker stays, shown to users
    std::string hostname;
    std::uint32_t threads = 0;
    Clock::time_point last_seen;
    std::optional<std::string> task;  // the task in hand
    Clock::time_point deadline;       // when the task in hand is overdue
    std::uint64_t tasks_done = 0;
  };

  // A worker said Ready: a worker not known yet is known and idle from now on; returns true then.
  // A known worker's Ready changes nothing but when it was last heard from, and returns false: it
  // answers a request for a new start that was sent before its first Ready came in (the
  // coordinator asks each time it hears from a worker it does not know). Identities are per
  // connection, so a worker that really started again comes with a new one; a task assigned to
  // this one since its first Ready is on its way to it and must stay its own.
  bool Ready(const std::string& identity, const proto::Ready& ready, Clock::time_point now);
  // Marks a known worker as heard from; false for a worker not known.
  bool Seen(const std::string& identity, Clock::time_point now);
  bool Known(const std::string& identity) const { return workers_.contains(identity); }

  // The idle worker that has waited longest, made busy with `task_id` until `deadline`.
  std::optional<std::string> Assign(const std::string& task_id, Clock::time_point deadline);
  bool HasIdle() const { return !idle_.empty(); }
  // The task in hand of a worker, if any.
  std::optional<std::string> TaskOf(const std::string& identity) const;
  // The worker finished its task: idle again.
  void Done(const std::string& identity);

  // Forgets a worker; returns the task it had in hand.
  std::optional<std::string> Remove(const std::string& identity);
  // Workers silent since `silent_since`, or holding a task past its deadline.
  std::vector<std::string> Lost(Clock::time_point now, Clock::time_point silent_since) const;

  std::vector<std::string> Identities() const;
  std::vector<proto::WorkerInfo> List(Clock::time_point now, double now_unix_s) const;
  std::size_t size() const { return workers_.size(); }
  // The threads of all known workers together.
  std::uint32_t threads() const;

 private:
  std::map<std::string, Worker> workers_;
  std::deque<std::string> idle_;
  std::uint64_t next_id_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_WORKER_TABLE_H_
