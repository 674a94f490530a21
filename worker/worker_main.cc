// evoslam-worker: evaluates fitness and evolves islands for an evoslam-coordinator.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <string>

#include "common/util/error.h"
#include "common/util/program_options.h"
#include "common/util/stop_signals.h"
#include "worker/worker.h"

int main(int argc, char** argv) {
  evoslam::StopSignals signals;  // first, so every thread inherits the blocked signals
  evoslam::WorkerOptions options;
  std::string server_key, secret_key, log_level = "info";

  CLI::App app{"evoslam-worker: runs tasks for an evoslam-coordinator"};
  app.add_option("--connect", options.endpoint, "the coordinator's worker endpoint")
      ->capture_default_str();
  app.add_option("--threads", options.threads, "OpenMP threads per task (0: all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  app.add_option("--cache-dir", options.cache_dir,
                 "where datasets are kept by hash (default: a private temporary folder)");
  app.add_option("--curve-server-key", server_key, "the coordinator's public key file (.pub)")
      ->check(CLI::ExistingFile);
  app.add_option("--curve-key", secret_key, "this worker's secret key file (.key)")
      ->check(CLI::ExistingFile);
  app.add_option("--heartbeat", options.heartbeat_seconds, "seconds between heartbeats")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 60.0));
  app.add_option("--liveness", options.liveness,
                 "heartbeats missed before the coordinator counts as gone")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option("--max-backoff", options.max_backoff_seconds,
                 "longest wait between two reconnections, s")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 3600.0));
  app.add_option("--grace", options.grace_seconds,
                 "on SIGTERM, seconds the task in hand may take before it is handed back")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3600.0));
  evoslam::AddLogLevelOption(app, log_level);
  if (const auto status = evoslam::ParseProgramOptions(app, argc, argv, log_level)) return *status;
  bool clean = true;
  try {
    if (server_key.empty() != secret_key.empty()) {
      throw evoslam::Error("CURVE needs both --curve-server-key and --curve-key");
    }
    if (!server_key.empty()) options.curve = evoslam::LoadCurveClientKeys(server_key, secret_key);
    zmq::context_t context;
    evoslam::Worker worker(context, options);
    clean = worker.Run(signals.token());
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  spdlog::shutdown();
  // A task handed back may still be computing; the process ends without waiting for it.
  if (!clean) std::_Exit(0);
  return 0;
}
