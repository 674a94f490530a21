#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/job_run.h"
#include "cli/localize_args.h"
#include "cli/service_session.h"

namespace evoslam::cli {
namespace {

void Run(const LocalizeArgs& a) {
  CheckJobRunArgs(a.run);
  const LocalizeOptions options = OptionsFrom(a);
  ServiceSession session(
      a.run.service,
      ChooseEmbeddedLayout(
          options.estimator.optimizer == OptimizerKind::kIsland ? options.estimator.islands : 1,
          a.run.workers, a.run.threads));
  const proto::JobSpec spec = JobFrom(a, options, session.client());
  RunJob(
      session.client(), spec, a.run,
      "localizing with " + a.fitness + " / " + a.estimator + " / " + spec.localize().optimizer());
}

}  // namespace

void AddLocalizeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("localize", "Continual localization of a log in a known map");
  auto a = std::make_shared<LocalizeArgs>();
  AddLocalizeJobOptions(cmd, *a, true);
  AddJobRunOptions(cmd, a->run);
  AddJobOutputOptions(cmd, a->run);
  cmd->callback([a, cmd] {
    NoteGivenOptions(cmd, *a);
    Run(*a);
  });
}

}  // namespace evoslam::cli
