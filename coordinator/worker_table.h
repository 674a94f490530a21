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
// when each was last heard from. A worker that fails (its own faults, invalid results) is taken
// out of the pool for a while: quarantined, it stays known but gets no work. The quarantine is
// kept by socket identity and by the worker's instance, so reconnecting does not end it.
class WorkerTable {
 public:
  using Clock = std::chrono::steady_clock;

  struct Worker {
    std::string id;  // "w-N": stable while the worker stays, shown to users
    std::string hostname;
    std::uint32_t threads = 0;
    Clock::time_point last_seen;
    std::optional<std::string> task;  // the task in hand
    Clock::time_point assigned;       // when it was given the task in hand
    Clock::time_point deadline;       // when the task in hand is overdue
    std::uint64_t tasks_done = 0;
    std::string instance;  // drawn by the worker process; empty from one that sends none
    int faults = 0;        // its own faults in a row
    std::optional<Clock::time_point> quarantined_until;
    std::string quarantine_reason;
  };

  struct Arrival {
    bool is_new = false;  // false: a repeated Ready
    // The same worker's old connection (same instance), forgotten, and the task it held.
    std::optional<std::string> replaced;
    std::optional<std::string> replaced_task;
    bool quarantined = false;  // it is known, but out of the pool for now
  };

  // A worker said Ready: a worker not known yet is known and idle from now on (is_new), unless
  // it is quarantined. A known worker's Ready changes nothing but when it was last heard from: it
  // answers a request for a new start that was sent before its first Ready came in (the
  // coordinator asks each time it hears from a worker it does not know). Identities are per
  // connection, so a worker that really started again comes with a new one; a task assigned to
  // this one since its first Ready is on its way to it and must stay its own. A new connection
  // of a known instance replaces the old one (a worker that gave up on a stalled coordinator and
  // reconnected): the old entry's id, counts and quarantine carry over, and its task is returned.
  Arrival Ready(const std::string& identity, const proto::Ready& ready, Clock::time_point now);
  // Marks a known worker as heard from; false for a worker not known.
  bool Seen(const std::string& identity, Clock::time_point now);
  bool Known(const std::string& identity) const { return workers_.contains(identity); }

  // The idle worker that has waited longest, made busy with `task_id` from `now` until
  // `deadline`.
  std::optional<std::string> Assign(const std::string& task_id, Clock::time_point now,
                                    Clock::time_point deadline);
  bool HasIdle() const { return !idle_.empty(); }
  // The task in hand of a worker, if any.
  std::optional<std::string> TaskOf(const std::string& identity) const;
  // How long a worker has held its task in hand by `now`; nullopt when it holds none.
  std::optional<Clock::duration> HeldFor(const std::string& identity, Clock::time_point now) const;
  // The worker finished its task: idle again.
  void Done(const std::string& identity);
  // The worker could not run its task through its own fault: idle again; returns its faults in a
  // row.
  int Failed(const std::string& identity);
  // Takes a worker out of the pool until `until`; it keeps no task (the caller returns it).
  std::optional<std::string> Quarantine(const std::string& identity, Clock::time_point until,
                                        const std::string& reason);
  // Ends the quarantines over by `now`; returns the identities back in the pool.
  std::vector<std::string> Release(Clock::time_point now);

  // Forgets a worker; returns the task it had in hand.
  std::optional<std::string> Remove(const std::string& identity);
  // Workers silent since `silent_since`, or holding a task past its deadline.
  std::vector<std::string> Lost(Clock::time_point now, Clock::time_point silent_since) const;

  std::vector<std::string> Identities() const;
  std::vector<proto::WorkerInfo> List(Clock::time_point now, double now_unix_s) const;
  std::size_t size() const { return workers_.size(); }
  // Of the known workers, those holding a task, and those quarantined.
  std::size_t busy() const;
  std::size_t quarantined() const;
  // The threads of all known workers together.
  std::uint32_t threads() const;

 private:
  struct Penalty {
    Clock::time_point until;
    std::string reason;
  };
  static std::vector<std::string> PenaltyKeys(const std::string& identity, const Worker& w);

  std::map<std::string, Worker> workers_;
  // Quarantines by "c:" identity and "i:" instance, outliving the entries they were given to.
  std::map<std::string, Penalty> penalties_;
  std::deque<std::string> idle_;
  std::uint64_t next_id_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_WORKER_TABLE_H_
