#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/job_client.h"
#include "cli/localize_args.h"
#include "cli/service_session.h"
#include "common/util/error.h"

namespace evoslam::cli {
namespace {

void Run(const LocalizeArgs& a) {
  const LocalizeOptions options = OptionsFrom(a);
  if (!a.service.coordinator.empty() && (a.given.contains("--workers"))) {
    throw CLI::ValidationError(
        "--workers sets the embedded workers; with --coordinator, start "
        "evoslam-worker processes instead");
  }
  if (a.service.coordinator.empty() && a.detach) {
    throw CLI::ValidationError(
        "--detach needs --coordinator: an embedded job ends with the command");
  }
  ServiceSession session(
      a.service,
      ChooseEmbeddedLayout(
          options.estimator.optimizer == OptimizerKind::kIsland ? options.estimator.islands : 1,
          a.workers, a.threads));
  ServiceClient& client = session.client();

  const proto::JobSpec spec = JobFrom(a, options, client);
  const std::string job_id = client.Submit(spec);
  if (a.detach) {
    std::printf("%s\n", job_id.c_str());
    return;
  }
  spdlog::info("{}: localizing with {} / {} / {}", job_id, a.fitness, a.estimator,
               spec.localize().optimizer());
  const std::vector<proto::ResultFile> files = FollowToResult(client, job_id);
  WriteResultFiles(files, a.out);
  std::string names;
  for (const proto::ResultFile& f : files) {
    if (f.name() == "summary.txt") std::printf("%s", f.content().c_str());
    names += (names.empty() ? "" : ",") + f.name();
  }
  std::printf("  wrote %s/{%s}\n", a.out.c_str(), names.c_str());
}

}  // namespace

void AddLocalizeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("localize", "Continual localization of a log in a known map");
  auto a = std::make_shared<LocalizeArgs>();
  AddLocalizeJobOptions(cmd, *a, true);
  AddLocalizeRunOptions(cmd, *a);
  cmd->add_flag("--detach", a->detach, "with --coordinator: print the job id and return at once");
  cmd->add_option("--out", a->out, "output directory");
  cmd->callback([a, cmd] {
    NoteGivenOptions(cmd, *a);
    if (a->out.empty() && !a->detach) throw CLI::RequiredError("--out");
    Run(*a);
  });
}

}  // namespace evoslam::cli
