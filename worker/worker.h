#ifndef EVOSLAM_WORKER_WORKER_H_
#define EVOSLAM_WORKER_WORKER_H_

#include <zmq.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>

#include "common/protocol/zmq_io.h"

namespace evoslam {

struct WorkerOptions {
  std::string endpoint = "tcp://127.0.0.1:5556";
  int threads = 0;                  // OpenMP threads per task; 0: all the cores
  std::filesystem::path cache_dir;  // datasets by hash; empty: a private temporary folder
  std::optional<CurveClientKeys> curve;
  double heartbeat_seconds = 1.0;
  int liveness = 3;                    // heartbeats missed before the coordinator counts as gone
  double first_backoff_seconds = 1.0;  // reconnection waits double from here ...
  double max_backoff_seconds = 32.0;   // ... up to here
  double grace_seconds = 10.0;         // on stop, how long the task in hand may take to finish
  std::string hostname;                // empty: this host's name
  bool quiet = false;  // comings and goings logged at debug level instead of info (embedded)
};

// A worker process's loop: a DEALER socket to the coordinator, one task at a time computed on a
// thread of its own while the loop keeps the heartbeats going (the Paranoid Pirate worker). When
// the coordinator falls silent the worker reconnects, waiting longer each time (exponential
// backoff). On stop it finishes the task in hand if it can within the grace time, else hands it
// back, and says goodbye.
class Worker {
 public:
  Worker(zmq::context_t& context, WorkerOptions options);
  ~Worker();
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Serves until `stop` is requested. Returns false when a task was still computing and had to
  // be abandoned (handed back): the caller should then end the process without waiting for it.
  bool Run(std::stop_token stop);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace evoslam

#endif  // EVOSLAM_WORKER_WORKER_H_
