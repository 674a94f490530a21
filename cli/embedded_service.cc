#include "cli/embedded_service.h"

#include <omp.h>

#include <algorithm>

namespace evoslam::cli {
namespace {

constexpr const char* kClients = "inproc://evoslam-clients";
constexpr const char* kWorkers = "inproc://evoslam-workers";

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

}  // namespace evoslam::cli
