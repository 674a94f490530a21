#ifndef EVOSLAM_CLI_EMBEDDED_SERVICE_H_
#define EVOSLAM_CLI_EMBEDDED_SERVICE_H_

#include <zmq.hpp>

#include <cstddef>
#include <memory>
#include <thread>
#include <vector>

#include "common/service/service_client.h"
#include "common/util/temp_dir.h"
#include "coordinator/coordinator.h"
#include "worker/worker.h"

namespace evoslam::cli {

// A coordinator and `workers` workers inside this process, talking over inproc sockets: a job
// run here takes exactly the path it takes on a cluster, so its outputs are the same.
class EmbeddedService {
 public:
  EmbeddedService(std::size_t workers, int threads_per_worker);
  ~EmbeddedService();
  EmbeddedService(const EmbeddedService&) = delete;
  EmbeddedService& operator=(const EmbeddedService&) = delete;

  zmq::context_t& context() { return context_; }
  ClientOptions client_options() const;

 private:
  zmq::context_t context_;
  TempDir dir_;
  std::unique_ptr<Coordinator> coordinator_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::stop_source stop_workers_, stop_coordinator_;
  std::vector<std::jthread> worker_threads_;
  std::jthread coordinator_thread_;
};

// How many embedded workers, with how many threads each, suit a job of `islands` islands (1 for
// a single algorithm) on this host: islands spread over workers, the cores over the workers.
struct EmbeddedLayout {
  std::size_t workers = 1;
  int threads = 1;
};
EmbeddedLayout ChooseEmbeddedLayout(std::size_t islands, std::size_t workers, int threads);

// The most workers this process can embed: each holds a socket and an eventfd, within the files
// the process may open (ulimit -n) and the sockets a ZeroMQ context may hold.
std::size_t MaxEmbeddedWorkers();

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_EMBEDDED_SERVICE_H_
