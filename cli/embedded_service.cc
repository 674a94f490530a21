#include "cli/embedded_service.h"

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <limits>

namespace evoslam::cli {
namespace {

constexpr const char* kClients = "inproc://evoslam-clients";
constexpr const char* kWorkers = "inproc://evoslam-workers";

// A worker's socket and its compute thread's eventfd, and room for a file it writes.
constexpr std::size_t kFilesPerWorker = 3;
// The coordinator's sockets, database and eventfd, the client's socket, the log being read,
// ZeroMQ's own: the files that do not grow with the workers.
constexpr std::size_t kFilesBesidesWorkers = 64;
constexpr std::size_t kSocketsBesidesWorkers = 8;

}  // namespace

EmbeddedService::EmbeddedService(std::size_t workers, int threads_per_worker)
    : dir_("evoslam-embedded") {
  CoordinatorOptions options;
  options.clients_endpoint = kClients;
  options.workers_endpoint = kWorkers;
  options.db = dir_ / "jobs.db";
  // The database goes with the process: checkpoints could never be resumed from.
  options.checkpoint_seconds = 1e12;
  options.quiet = true;
  coordinator_ = std::make_unique<Coordinator>(context_, options);
  coordinator_thread_ =
      std::jthread([this, token = stop_coordinator_.get_token()] { coordinator_->Run(token); });
  for (std::size_t i = 0; i < std::max<std::size_t>(1, workers); ++i) {
    WorkerOptions w;
    w.endpoint = kWorkers;
    w.threads = threads_per_worker;
    w.grace_seconds = 0.0;
    w.quiet = true;
    workers_.push_back(std::make_unique<Worker>(context_, w));
    worker_threads_.emplace_back([worker = workers_.back().get(),
                                  token = stop_workers_.get_token()] { worker->Run(token); });
  }
}

EmbeddedService::~EmbeddedService() {
  stop_workers_.request_stop();
  worker_threads_.clear();
  stop_coordinator_.request_stop();
  if (coordinator_thread_.joinable()) coordinator_thread_.join();
}

ClientOptions EmbeddedService::client_options() const {
  ClientOptions options;
  options.endpoint = kClients;
  // Nothing can be lost between threads; a long silence is a long step, not a dead peer.
  options.timeout_seconds = 3600.0;
  return options;
}

EmbeddedLayout ChooseEmbeddedLayout(std::size_t islands, std::size_t workers, int threads) {
  const auto cores = static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
  EmbeddedLayout layout;
  layout.workers = workers > 0 ? workers : std::clamp<std::size_t>(islands, 1, cores);
  layout.threads =
      threads > 0 ? threads : static_cast<int>(std::max<std::size_t>(1, cores / layout.workers));
  return layout;
}

std::size_t MaxEmbeddedWorkers() {
  rlimit files{};
  std::size_t by_files = 0;
  if (::getrlimit(RLIMIT_NOFILE, &files) != 0 || files.rlim_cur == RLIM_INFINITY) {
    by_files = std::numeric_limits<std::size_t>::max();
  } else if (files.rlim_cur > kFilesBesidesWorkers) {
    by_files = (static_cast<std::size_t>(files.rlim_cur) - kFilesBesidesWorkers) / kFilesPerWorker;
  }
  const std::size_t by_sockets = ZMQ_MAX_SOCKETS_DFLT - kSocketsBesidesWorkers;
  return std::min(by_files, by_sockets);
}

}  // namespace evoslam::cli
