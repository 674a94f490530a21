#include "cli/job_run.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <vector>

#include "cli/embedded_service.h"
#include "cli/job_client.h"
#include "cli/option_parsing.h"

namespace evoslam::cli {

void AddJobRunOptions(CLI::App* cmd, JobRunArgs& a) {
  cmd->add_option("--threads", a.threads,
                  "embedded: threads per worker (default: the cores shared among the workers)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--workers", a.workers,
                  "embedded: workers in this process (default: one per island, at most one "
                  "per core)")
      ->check(CLI::Range(1, 1024));
  AddServiceOptions(cmd, a.service, true);
}

void AddJobOutputOptions(CLI::App* cmd, JobRunArgs& a) {
  cmd->add_flag("--detach", a.detach, "with --coordinator: print the job id and return at once");
  cmd->add_option("--out", a.out, "output folder; required unless --detach")->type_name("DIR");
}

void CheckJobRunArgs(const JobRunArgs& a) {
  if (a.out.empty() && !a.detach) throw CLI::RequiredError("--out");
  if (!a.out.empty()) CheckOutputFolder("--out", a.out);
  if (a.workers > MaxEmbeddedWorkers()) {
    throw CLI::ValidationError(
        "--workers", std::to_string(a.workers) + " is more than this process can embed: at most " +
                         std::to_string(MaxEmbeddedWorkers()) +
                         " within its limits on open files (ulimit -n) and on ZeroMQ sockets");
  }
  if (!a.service.coordinator.empty() && a.workers > 0) {
    throw CLI::ValidationError(
        "--workers sets the embedded workers; with --coordinator, start "
        "evoslam-worker processes instead");
  }
  if (a.service.coordinator.empty() && a.detach) {
    throw CLI::ValidationError(
        "--detach needs --coordinator: an embedded job ends with the command");
  }
}

void RunJob(ServiceClient& client, const proto::JobSpec& spec, const JobRunArgs& a,
            const std::string& what) {
  const std::string job_id = client.Submit(spec);
  if (a.detach) {
    std::printf("%s\n", job_id.c_str());
    return;
  }
  // An embedded job is the command's own work: its id would mean nothing to the user.
  const bool embedded = a.service.coordinator.empty();
  if (embedded) {
    spdlog::info("{}", what);
  } else {
    spdlog::info("{}: {}", job_id, what);
  }
  const std::vector<proto::ResultFile> files = FollowToResult(client, job_id, !embedded);
  WriteResultFiles(files, a.out);
  std::string names;
  for (const proto::ResultFile& f : files) {
    if (f.name() == "summary.txt") std::printf("%s", f.content().c_str());
    names += (names.empty() ? "" : ",") + f.name();
  }
  std::printf("  wrote %s/{%s}\n", a.out.c_str(), names.c_str());
}

}  // namespace evoslam::cli
