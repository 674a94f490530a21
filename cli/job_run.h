#ifndef EVOSLAM_CLI_JOB_RUN_H_
#define EVOSLAM_CLI_JOB_RUN_H_

#include <CLI/CLI.hpp>

#include <cstddef>
#include <string>

#include "cli/service_options.h"
#include "common/service/service_client.h"
#include "evoslam/service.pb.h"

namespace evoslam::cli {

// What a command that runs one job (localize, slam) takes besides the job itself: where the job
// runs and where its files go.
struct JobRunArgs {
  int threads = 0;          // embedded: threads per worker; 0: the cores shared among the workers
  std::size_t workers = 0;  // embedded; 0: one per island, at most one per core
  bool detach = false;
  std::string out;
  ServiceArgs service;
};

// Adds --threads and --workers (embedded) and the service options.
void AddJobRunOptions(CLI::App* cmd, JobRunArgs& a);
// Adds --detach and --out.
void AddJobOutputOptions(CLI::App* cmd, JobRunArgs& a);
// Refuses, as command-line errors, options that cannot go together: --workers with
// --coordinator, --detach without it, no --out without --detach.
void CheckJobRunArgs(const JobRunArgs& a);

// Submits the job. With --detach prints its id; else follows it to its end (progress bars on a
// terminal), writes its files into --out, prints its summary.txt and the files written. `what`
// says what the job does, for the log.
void RunJob(ServiceClient& client, const proto::JobSpec& spec, const JobRunArgs& a,
            const std::string& what);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_JOB_RUN_H_
