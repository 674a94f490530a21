#include <zmq.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>

#include "cli/commands.h"
#include "cli/job_client.h"
#include "cli/service_options.h"
#include "common/service/job_progress.h"
#include "common/service/job_state.h"
#include "common/service/service_client.h"
#include "common/util/counted.h"
#include "common/util/error.h"

namespace evoslam::cli {
namespace {

struct JobArgs {
  ServiceArgs service;
  std::string job_id;
  std::string out;
};

// A client of the coordinator the arguments name, with the context it lives in.
struct Connection {
  explicit Connection(const ServiceArgs& args) : client(context, ClientOptionsFrom(args)) {}
  zmq::context_t context;
  ServiceClient client;
};

std::string When(double unix_s) {
  if (unix_s <= 0) return "-";
  const auto t = static_cast<std::time_t>(unix_s);
  std::tm tm{};
  localtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &tm);
  return text;
}

void PrintStatus(const proto::JobStatus& s) {
  std::printf("%s  %s  %s", s.job_id().c_str(), std::string(JobStateName(s.state())).c_str(),
              s.phase().c_str());
  if (s.total() > 0) {
    std::printf(" %llu/%llu scans", static_cast<unsigned long long>(s.done()),
                static_cast<unsigned long long>(s.total()));
  }
  if (const std::string step = StepText(s); !step.empty()) std::printf(" · %s", step.c_str());
  std::printf("  submitted %s", When(s.submitted_unix_s()).c_str());
  if (s.finished_unix_s() > 0) std::printf("  finished %s", When(s.finished_unix_s()).c_str());
  if (!s.error().empty()) std::printf("\n  error: %s", s.error().c_str());
  std::printf("\n");
}

CLI::App* JobCommand(CLI::App& app, const char* name, const char* help,
                     const std::shared_ptr<JobArgs>& a, bool takes_id) {
  auto* cmd = app.add_subcommand(name, help);
  AddServiceOptions(cmd, a->service, false);
  if (takes_id)
    cmd->add_option("job", a->job_id, "the job's id: job- and 32 hex digits")->required();
  return cmd;
}

}  // namespace

void AddJobCommands(CLI::App& app) {
  auto a = std::make_shared<JobArgs>();
  JobCommand(app, "jobs", "List the coordinator's jobs", a, false)->callback([a] {
    Connection c(a->service);
    const auto jobs = c.client.Jobs();
    for (const proto::JobStatus& s : jobs) PrintStatus(s);
    if (jobs.empty()) std::printf("no jobs\n");
  });
  JobCommand(app, "status", "Show one job's state and progress", a, true)->callback([a] {
    Connection c(a->service);
    PrintStatus(c.client.Status(a->job_id));
  });
  JobCommand(app, "watch", "Follow a job to its end with a progress bar", a, true)->callback([a] {
    Connection c(a->service);
    const proto::JobStatus s = WatchWithProgress(c.client, a->job_id);
    PrintStatus(s);
    if (s.state() != proto::JOB_STATE_SUCCEEDED) {
      throw Error(a->job_id + " " + std::string(JobStateName(s.state())));
    }
  });
  auto* result = JobCommand(app, "result", "Write a finished job's files", a, true);
  result->add_option("--out", a->out, "output folder")->type_name("DIR")->required();
  result->callback([a] {
    Connection c(a->service);
    const auto files = c.client.Result(a->job_id);
    WriteResultFiles(files, a->out);
    for (const proto::ResultFile& f : files)
      std::printf("%s/%s\n", a->out.c_str(), f.name().c_str());
  });
  JobCommand(app, "cancel", "Cancel a queued or running job", a, true)->callback([a] {
    Connection c(a->service);
    PrintStatus(c.client.Cancel(a->job_id));
  });
  JobCommand(app, "workers", "List the workers connected to the coordinator", a, false)
      ->callback([a] {
        Connection c(a->service);
        const auto workers = c.client.Workers();
        const double now =
            std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                .count();
        for (const proto::WorkerInfo& w : workers) {
          std::string state = w.busy() ? "busy" : "idle";
          if (w.quarantined_until_unix_s() > 0) {
            state = "quarantined for " +
                    std::to_string(std::max(0L, std::lround(w.quarantined_until_unix_s() - now))) +
                    " s more (" + w.quarantine_reason() + ")";
          }
          std::printf("%s  %s  %s  %s  %s done\n", w.worker_id().c_str(), w.hostname().c_str(),
                      Counted(w.threads(), "thread").c_str(), state.c_str(),
                      Counted(w.tasks_done(), "task").c_str());
        }
        if (workers.empty()) std::printf("no workers connected\n");
      });
}

}  // namespace evoslam::cli
