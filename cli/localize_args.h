#ifndef EVOSLAM_CLI_LOCALIZE_ARGS_H_
#define EVOSLAM_CLI_LOCALIZE_ARGS_H_

#include <CLI/CLI.hpp>

#include <cstdint>
#include <set>
#include <string>

#include "cli/job_run.h"
#include "common/localization/localizer.h"
#include "common/optim/particle_swarm.h"
#include "common/service/service_client.h"
#include "evoslam/service.pb.h"

namespace evoslam::cli {

// The command line of a localization job, shared by `localize` and `tune`.
struct LocalizeArgs {
  std::string map, map_from_log, log, start, relations;
  std::string fitness = "f3", estimator = "2d", optimizer = "de", strategy = "rand1exp";
  double f2_base = FitnessParams{}.f2_base, f2_slope = FitnessParams{}.f2_slope;
  double f3_cap = FitnessParams{}.f3_cap;
  std::size_t population = 25, generations = 25, max_scans = 0;
  double f = 0.6, cr = 0.9, window = 0.6, heading_window = 30.0, heading_step = 0.5;
  PsoParams pso;
  std::string pso_neighbourhood = "global";
  std::string crossover = "two-point";
  double ga_grid = 0.01, ga_bit_flip = 0.0;
  std::size_t islands = 4, migration_interval = 5, migrants = 1;
  std::string island_algorithm = "de", topology = "ring", migration_policy = "best-replace-worst";
  std::string preset;
  std::set<std::string> given;  // options set on the command line, which override a preset
  double exhaustive_step = 0.01, max_range = 0.0, resolution = 0.05;
  std::uint64_t seed = 1;
  bool use_odometry = false, lenient = false;
  JobRunArgs run;
};

// Adds the job's options to `cmd` (--islands too unless the command sets it itself), with the
// deprecated spellings of their names.
void AddLocalizeJobOptions(CLI::App* cmd, LocalizeArgs& a, bool with_islands);
// Records which options were given, so they override a preset.
void NoteGivenOptions(const CLI::App* cmd, LocalizeArgs& a);

// The job's settings. Values the parser could not check alone are refused as command-line
// errors (CLI::ValidationError), before any file is read.
LocalizeOptions OptionsFrom(const LocalizeArgs& a);

// The job the command line describes, its datasets uploaded through `client`.
proto::JobSpec JobFrom(const LocalizeArgs& a, const LocalizeOptions& options,
                       ServiceClient& client);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_LOCALIZE_ARGS_H_
