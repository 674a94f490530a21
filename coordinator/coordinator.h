#ifndef EVOSLAM_COORDINATOR_COORDINATOR_H_
#define EVOSLAM_COORDINATOR_COORDINATOR_H_

#include <zmq.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <stop_token>
#include <string>

#include "coordinator/http_address.h"

namespace evoslam {

struct CoordinatorOptions {
  std::string clients_endpoint = "tcp://127.0.0.1:5555";
  std::string workers_endpoint = "tcp://127.0.0.1:5556";
  std::filesystem::path db;
  // CURVE: the coordinator's secret key and the public keys it accepts. Empty secret: plain
  // TCP (then bind only to trusted interfaces; 127.0.0.1 is the default).
  std::string curve_secret_key;
  std::set<std::string> client_keys, worker_keys;
  // Clients that see every job (also among client_keys). Any other sees only the jobs its key
  // submitted; with CURVE off every client is the same owner.
  std::set<std::string> admin_keys;

  std::size_t max_message_bytes = std::size_t{256} << 20;
  std::size_t max_dataset_bytes = std::size_t{256} << 20;
  std::size_t max_queued_jobs = 10000;  // jobs queued or running
  std::size_t max_running_jobs = 8;     // jobs whose threads run at once
  std::size_t max_watchers = 1000;
  std::size_t max_uploads = 64;  // uploads under way at once
  // An upload whose client sends nothing for this long is dropped: its client is gone.
  double upload_timeout_seconds = 60;
  // Bytes a client may keep stored (its datasets and its jobs' results); 0: no limit.
  std::uint64_t client_quota_bytes = 0;
  // Ended jobs (with their results) are dropped this long after they ended, and datasets no job
  // reads this long after they were last uploaded; 0: everything is kept.
  double retention_seconds = 0;
  double heartbeat_seconds = 1.0;
  int liveness = 3;                   // heartbeats missed before a worker counts as gone
  double task_timeout_seconds = 600;  // a task not answered by then is given to another worker
  // Times a task may lose its worker (silent, overdue, its connection closed while it computed)
  // before its job fails: a task that kills every worker it reaches must not kill them all. A
  // failure that is not the task's (a send to a closed connection, a stalled coordinator, a
  // worker's own fault or invalid answer) does not count.
  int max_task_attempts = 3;
  // A worker that fails this many tasks in a row through its own fault (its disk, its memory) is
  // out of the pool for `quarantine_seconds`; one that sends an invalid result is at once.
  int quarantine_after = 3;
  double quarantine_seconds = 60;
  // Least time between two saved checkpoints of a job: every epoch of a long search is saved,
  // but jobs of many millisecond epochs are not slowed by a database write each.
  double checkpoint_seconds = 1.0;
  bool quiet = false;  // comings and goings logged at debug level instead of info (embedded)
  // Where to serve Prometheus metrics over HTTP, at /metrics; none: nowhere.
  std::optional<HttpAddress> metrics_address;
};

// The service's hub. Clients submit jobs on one ROUTER socket; workers take tasks on another,
// one task at a time (the load-balancing broker), and both sides exchange heartbeats (the
// Paranoid Pirate pattern): a worker silent for `liveness` heartbeats, or holding a task past
// its deadline, is dropped and its task given to another. Each running job has a thread that
// holds its map and trajectory and posts its tasks. All state that matters is in the SQLite
// database: after a crash a coordinator restarted on the same file resumes every unfinished job
// from its last checkpoint.
class Coordinator {
 public:
  // Opens the database, binds both sockets and the metrics' HTTP server (throws Error naming the
  // endpoint when one cannot be bound) and queues the unfinished jobs found in the database.
  Coordinator(zmq::context_t& context, CoordinatorOptions options);
  ~Coordinator();
  Coordinator(const Coordinator&) = delete;
  Coordinator& operator=(const Coordinator&) = delete;

  // Serves until `stop` is requested. Jobs still running then are left to resume next time.
  void Run(std::stop_token stop);

  // The endpoints actually bound (a tcp port 0 or '*' resolved).
  std::string clients_endpoint() const;
  std::string workers_endpoint() const;
  // Where the metrics are served, "http://HOST:PORT/metrics" (a port 0 resolved); empty when
  // they are not.
  std::string metrics_url() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_COORDINATOR_H_
