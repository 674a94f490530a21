// evoslam-coordinator: the service's hub. See coordinator/README.md.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "common/protocol/curve_keys.h"
#include "common/protocol/zmq_io.h"
#include "common/util/error.h"
#include "common/util/program_options.h"
#include "common/util/stop_signals.h"
#include "coordinator/coordinator.h"
#include "coordinator/http_address.h"

int main(int argc, char** argv) {
  evoslam::StopSignals signals;  // first, so every thread inherits the blocked signals
  evoslam::CoordinatorOptions options;
  std::string curve_secret, log_level = "info";
  std::vector<std::filesystem::path> client_keys, worker_keys, admin_keys;
  double max_message_mb = 256, max_dataset_mb = 256, client_quota_mb = 10240, retention_hours = 720;

  CLI::App app{"evoslam-coordinator: holds jobs, hands their work to evoslam-worker processes"};
  app.add_option("--clients", options.clients_endpoint, "endpoint clients connect to")
      ->capture_default_str();
  app.add_option("--workers", options.workers_endpoint, "endpoint workers connect to")
      ->capture_default_str();
  app.add_option("--db", options.db, "SQLite database of jobs, datasets and checkpoints")
      ->required();
  app.add_option("--curve-secret-key", curve_secret,
                 "turn CURVE on with this secret key file (evoslam keygen)")
      ->check(CLI::ExistingFile);
  app.add_option("--client-keys", client_keys,
                 "public keys (.pub files or folders of them) of the clients to accept");
  app.add_option("--worker-keys", worker_keys,
                 "public keys (.pub files or folders of them) of the workers to accept");
  app.add_option("--admin-keys", admin_keys,
                 "public keys (.pub files or folders of them) of clients that see every job");
  app.add_option("--client-quota-mb", client_quota_mb,
                 "bytes a client may keep stored (its datasets and results), MiB; 0: no limit")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--retention-hours", retention_hours,
                 "ended jobs and datasets no job reads are dropped this long after they ended or "
                 "were uploaded; 0: kept for ever")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e7));
  app.add_option("--max-message-mb", max_message_mb, "largest message accepted, MiB")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 2000.0));
  app.add_option("--max-dataset-mb", max_dataset_mb, "largest dataset accepted, MiB")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 2000.0));
  app.add_option("--max-uploads", options.max_uploads, "uploads under way at once at most")
      ->capture_default_str()
      ->check(CLI::Range(1, 100'000));
  app.add_option("--upload-timeout", options.upload_timeout_seconds,
                 "seconds an upload may go without a chunk before it is dropped")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1e6));
  app.add_option("--max-queued-jobs", options.max_queued_jobs, "jobs queued or running at most")
      ->capture_default_str()
      ->check(CLI::Range(1, 10'000'000));
  app.add_option("--max-running-jobs", options.max_running_jobs, "jobs run at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  app.add_option("--heartbeat", options.heartbeat_seconds, "seconds between heartbeats")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 60.0));
  app.add_option("--liveness", options.liveness, "heartbeats missed before a worker is lost")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option("--task-timeout", options.task_timeout_seconds,
                 "seconds a task may take before it goes to another worker")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1e6));
  app.add_option("--max-task-attempts", options.max_task_attempts,
                 "times a task may lose its worker before its job fails")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  app.add_option("--quarantine-after", options.quarantine_after,
                 "tasks a worker fails in a row through its own fault before it leaves the pool")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  app.add_option("--quarantine", options.quarantine_seconds,
                 "seconds a failing worker stays out of the pool")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_option(
         "--checkpoint-interval", options.checkpoint_seconds,
         "least seconds between two saved checkpoints of a job (0: at every migration epoch)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  std::string metrics;
  app.add_option("--metrics", metrics,
                 "serve Prometheus metrics over HTTP at http://HOST:PORT/metrics "
                 "(e.g. 127.0.0.1:9464; port 0: any free port)")
      ->type_name("HOST:PORT")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            try {
              evoslam::ParseHttpAddress(text);
              return {};
            } catch (const evoslam::Error& e) {
              return e.what();
            }
          },
          ""));
  bool insecure = false;
  app.add_flag("--insecure", insecure,
               "listen on addresses other hosts reach without CURVE (anyone who reaches them "
               "may submit, list and cancel jobs, or work as a worker), and serve --metrics to "
               "them");
  evoslam::AddLogLevelOption(app, log_level);
  if (const auto status = evoslam::ParseProgramOptions(app, argc, argv, log_level)) return *status;
  try {
    options.max_message_bytes = static_cast<std::size_t>(max_message_mb * (1 << 20));
    options.max_dataset_bytes = static_cast<std::size_t>(max_dataset_mb * (1 << 20));
    options.client_quota_bytes = static_cast<std::uint64_t>(client_quota_mb * (1 << 20));
    options.retention_seconds = retention_hours * 3600;
    if (!curve_secret.empty()) {
      options.curve_secret_key = evoslam::ReadCurveKey(curve_secret);
      if (client_keys.empty() || worker_keys.empty()) {
        throw evoslam::Error("with CURVE on, give --client-keys and --worker-keys");
      }
      options.client_keys = evoslam::ReadPublicKeys(client_keys);
      options.worker_keys = evoslam::ReadPublicKeys(worker_keys);
      if (!admin_keys.empty()) options.admin_keys = evoslam::ReadPublicKeys(admin_keys);
    } else if (!client_keys.empty() || !worker_keys.empty() || !admin_keys.empty()) {
      throw evoslam::Error("--client-keys, --worker-keys and --admin-keys need --curve-secret-key");
    }
    if (curve_secret.empty()) {
      for (const std::string& endpoint : {options.clients_endpoint, options.workers_endpoint}) {
        if (evoslam::IsLoopbackEndpoint(endpoint)) continue;
        if (!insecure) {
          spdlog::error(
              "refusing to listen on {} without CURVE: anyone who reaches it could submit, read "
              "and cancel jobs or pose as a worker; give --curve-secret-key (docs/service.md, "
              "Security), or --insecure to run so on a network you trust",
              endpoint);
          return 2;
        }
        spdlog::warn(
            "listening on {} without CURVE (--insecure): anyone who reaches it may "
            "submit, read and cancel jobs, or pose as a worker",
            endpoint);
      }
    }
    if (!metrics.empty()) {
      options.metrics_address = evoslam::ParseHttpAddress(metrics);
      // CURVE or not: the metrics are plain HTTP, with no key to ask for.
      if (!options.metrics_address->IsLoopback()) {
        if (!insecure) {
          spdlog::error(
              "refusing to serve metrics on {}: anyone who reaches it could read them (jobs, "
              "workers, bytes stored); serve them on 127.0.0.1 for a scraper on this host (or "
              "behind a proxy), or give --insecure to serve them so on a network you trust",
              metrics);
          return 2;
        }
        spdlog::warn("serving metrics on {} to anyone who reaches it (--insecure)", metrics);
      }
    }
    zmq::context_t context;
    evoslam::Coordinator coordinator(context, options);
    coordinator.Run(signals.token());
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
