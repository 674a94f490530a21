#include "cli/localize_args.h"

#include <fmt/format.h>

#include "cli/job_client.h"
#include "cli/option_parsing.h"
#include "common/engine/archipelago.h"
#include "common/engine/presets.h"
#include "common/localization/localize_params.h"
#include "common/localization/pose_estimator.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"

namespace evoslam::cli {

void AddLocalizeJobOptions(CLI::App* cmd, LocalizeArgs& a, bool with_islands) {
  CLI::App* map = cmd->add_option_group("map", "The known map");
  map->add_option("--map", a.map, "known map: LineMap text file or map_server .yaml")
      ->type_name("FILE");
  map->add_option("--map-from-log", a.map_from_log,
                  "build an occupancy grid from this log's reference poses instead")
      ->type_name("FILE");
  map->require_option(1);
  AddDeprecatedName(
      cmd, "--grid-resolution",
      cmd->add_option("--resolution", a.resolution,
                      "cell size of the --map-from-log grid, metres per cell (map.yaml's "
                      "resolution)")
          ->check(PositiveNumber()));
  AddLogOption(cmd, "log", a.log, "CARMEN log to localize")->required();
  cmd->add_option("--start", a.start,
                  "start pose x,y,theta (m, m, rad); default: first scan's pose");
  cmd->add_flag("--use-odometry", a.use_odometry, "centre the window on the odometry prediction");
  cmd->add_option("--fitness", a.fitness, "f3 (L1 sum) or f2 (beams within tolerance)")
      ->check(OneOf({"f3", "f2"}));
  cmd->add_option("--f2-base", a.f2_base,
                  "F2: the tolerance at range 0, m; a grid map's cell is worth a try")
      ->check(NonNegativeNumber());
  cmd->add_option("--f2-slope", a.f2_slope,
                  "F2: the tolerance's growth per metre of simulated plus observed range")
      ->check(NonNegativeNumber());
  cmd->add_option("--f3-cap", a.f3_cap,
                  "F3: count each beam's difference up to this many metres (0: uncapped, the "
                  "papers' F3); 0.5 held best on real logs")
      ->check(NonNegativeNumber());
  cmd->add_option("--estimator", a.estimator, "2d (heading by brute force) or 3d")
      ->check(OneOf({"2d", "3d"}));
  cmd->add_option("--optimizer", a.optimizer,
                  "an engine algorithm (de, jde, pso, ...), island (an island model of "
                  "--island-algorithm) or exhaustive")
      ->check(OneOf(OptimizerNames()));
  cmd->add_option("--preset", a.preset,
                  "start from a paper's algorithm, settings and generation count (see "
                  "docs/engine.md); options given as well override them")
      ->check(OneOf(PresetNames()));
  cmd->add_option("--strategy", a.strategy, "DE strategy, e.g. rand1exp, best1bin");
  AddDeprecatedName(cmd, "--pop",
                    cmd->add_option("--population", a.population,
                                    "population, or particles (PSO); per island with islands")
                        ->check(CLI::Range(2, 100000)));
  AddDeprecatedName(cmd, "--gen",
                    cmd->add_option("--generations", a.generations, "generations")
                        ->check(CLI::Range(1, 1000000)));
  cmd->add_option("--F", a.f, "DE differential weight")->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--CR", a.cr, "DE crossover rate")->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--w", a.pso.inertia, "PSO inertia weight")->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--c1", a.pso.c1, "PSO pull towards each particle's best")
      ->check(CLI::Range(0.0, 4.0));
  cmd->add_option("--c2", a.pso.c2, "PSO pull towards the swarm's best")
      ->check(CLI::Range(0.0, 4.0));
  cmd->add_option("--vmax", a.pso.vmax_fraction,
                  "PSO velocity clamp per coordinate, as a fraction of the window")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--pso-neighbourhood", a.pso_neighbourhood,
                  "PSO: follow the swarm's best (global) or the best of two ring neighbours")
      ->check(OneOf({"global", "ring"}));
  cmd->add_option("--crossover", a.crossover, "SGA and aGA: two-point or uniform crossover")
      ->check(OneOf({"two-point", "uniform"}));
  cmd->add_option("--ga-grid", a.ga_grid,
                  "SGA and aGA: search grid of the binary chromosomes, m (0: none)")
      ->check(NonNegativeNumber());
  cmd->add_option("--ga-bit-flip", a.ga_bit_flip,
                  "SGA and aGA: probability of flipping each bit of a child (003: 0)")
      ->check(CLI::Range(0.0, 1.0));
  if (with_islands) {
    cmd->add_option("--islands", a.islands, "--optimizer island: number of islands")
        ->check(CLI::Range(std::size_t{1}, kMaxIslands));
  }
  cmd->add_option("--island-algorithm", a.island_algorithm,
                  "--optimizer island: the algorithm every island runs")
      ->check(OneOf(AlgorithmKindNames()));
  cmd->add_option("--migration-interval", a.migration_interval,
                  "--optimizer island: generations between migrations")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--migrants", a.migrants, "--optimizer island: migrants per island")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--topology", a.topology, "--optimizer island: who sends migrants to whom")
      ->check(OneOf({"ring", "bidirectional-ring", "fully-connected", "star", "random"}));
  cmd->add_option("--migration-policy", a.migration_policy,
                  "--optimizer island: which individuals leave and which they replace")
      ->check(OneOf({"best-replace-worst", "random-replace"}));
  cmd->add_option("--window", a.window, "side of the square search window, m")
      ->check(PositiveNumber());
  cmd->add_option("--heading-window", a.heading_window, "heading search half-width, degrees")
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_option("--heading-step", a.heading_step, "heading step, degrees")
      ->check(PositiveNumber());
  cmd->add_option("--exhaustive-step", a.exhaustive_step,
                  "lattice spacing of --optimizer exhaustive, m")
      ->check(PositiveNumber());
  cmd->add_option("--max-range", a.max_range, "simulation range limit, m (default: the scan's)")
      ->check(NonNegativeNumber());
  cmd->add_option("--max-scans", a.max_scans, "localize only the first N scans, 0: all");
  cmd->add_option("--relations", a.relations, "relations file for the relative error")
      ->type_name("FILE");
  cmd->add_option("--seed", a.seed, "random seed");
  cmd->add_flag("--lenient", a.lenient, "skip malformed log lines and report how many");
}

void NoteGivenOptions(const CLI::App* cmd, LocalizeArgs& a) {
  for (const CLI::Option* option : cmd->get_options()) {
    if (option->count() > 0) a.given.insert(option->get_name());
  }
}

LocalizeOptions OptionsFrom(const LocalizeArgs& a) try {
  LocalizeOptions options;
  EstimatorParams& e = options.estimator;
  e.fitness.kind = ParseFitnessKind(a.fitness);
  e.fitness.f2_base = a.f2_base;
  e.fitness.f2_slope = a.f2_slope;
  e.fitness.f3_cap = a.f3_cap;
  e.estimator = ParseEstimatorKind(a.estimator);
  // A preset supplies the algorithm and its settings; options given explicitly override them.
  const bool preset = !a.preset.empty();
  const auto use = [&](const char* option) { return !preset || a.given.contains(option); };
  if (preset) {
    const Preset& p = FindPreset(a.preset);
    e.algorithm = p.algorithm;
    e.generations = p.stop.max_generations;
  }
  if (use("--optimizer")) e.optimizer = ParseOptimizer(a.optimizer, e.algorithm);
  if (e.optimizer == OptimizerKind::kIsland && use("--island-algorithm"))
    e.algorithm.kind = ParseAlgorithmKind(a.island_algorithm);
  AlgorithmSpec& s = e.algorithm;
  if (use("--strategy")) s.de.strategy = ParseDeStrategy(a.strategy);
  if (use("--population")) {
    const std::size_t n = a.population;
    s.de.population = s.jde.population = s.pso.particles = s.ga.population = n;
    // The multi-objective EAs keep their papers' proportions: lambda = 7 mu (002), and four
    // recombinations to one mutation.
    s.mu_plus_lambda.mu = n;
    s.mu_plus_lambda.lambda = 7 * n;
    s.immune.population = n;
    s.immune.recombinations = n - n / 5;
    s.immune.mutations = n / 5;
  }
  if (use("--crossover")) s.ga.crossover = ParseGaCrossover(a.crossover);
  if (use("--ga-grid")) s.ga.grid_step = a.ga_grid;
  if (use("--ga-bit-flip")) s.ga.bit_flip = a.ga_bit_flip;
  if (use("--F")) s.de.f = a.f;
  if (use("--CR")) s.de.cr = a.cr;
  if (use("--w")) s.pso.inertia = a.pso.inertia;
  if (use("--c1")) s.pso.c1 = a.pso.c1;
  if (use("--c2")) s.pso.c2 = a.pso.c2;
  if (use("--vmax")) s.pso.vmax_fraction = a.pso.vmax_fraction;
  if (use("--pso-neighbourhood")) s.pso.neighbourhood = ParsePsoNeighbourhood(a.pso_neighbourhood);
  if (use("--generations")) e.generations = a.generations;
  e.islands = a.islands;
  e.migration.interval = a.migration_interval;
  e.migration.migrants = a.migrants;
  e.migration.topology = ParseTopology(a.topology);
  e.migration.policy = ParseMigrationPolicy(a.migration_policy);
  e.window = a.window;
  e.heading_half_window = Radians(a.heading_window);
  e.heading_step = Radians(a.heading_step);
  e.exhaustive_step = a.exhaustive_step;
  // The searches sized by a step are refused naming the flag; ValidateEstimatorParams checks the
  // same for jobs that come over the socket.
  if (!(e.heading_step >= kMinHeadingStep) || !(HeadingsPerScan(e) <= kMaxHeadingsPerScan)) {
    throw CLI::ValidationError(
        "--heading-step", fmt::format("{} degrees over a window of +-{} degrees tries {:.0f} "
                                      "headings per scan; the step must be at least {} degrees and "
                                      "the headings at most {:.0f}",
                                      a.heading_step, a.heading_window, HeadingsPerScan(e),
                                      Degrees(kMinHeadingStep), kMaxHeadingsPerScan));
  }
  if (e.optimizer == OptimizerKind::kExhaustive &&
      !(LatticePosesPerScan(e) <= kMaxLatticePosesPerScan)) {
    throw CLI::ValidationError(
        "--exhaustive-step",
        fmt::format("{} m over a {} m window tries {:.0f} poses per scan, more than {:.0f}",
                    a.exhaustive_step, a.window, LatticePosesPerScan(e), kMaxLatticePosesPerScan));
  }
  ValidateEstimatorParams(e);
  options.use_odometry = a.use_odometry;
  options.seed = a.seed;
  options.max_range = a.max_range;
  options.max_scans = a.max_scans;
  if (!a.start.empty()) options.start = ParsePose(a.start, "--start");
  return options;
} catch (const Error& e) {
  throw CLI::ValidationError(e.what());
}

proto::JobSpec JobFrom(const LocalizeArgs& a, const LocalizeOptions& options,
                       ServiceClient& client) {
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_LOCALIZE);
  proto::LocalizeParams& p = *spec.mutable_localize();
  p = ToProto(options);
  p.set_map(a.map.empty() ? "grid from " + a.map_from_log : a.map);
  p.set_log(a.log);
  p.set_preset(a.preset);
  p.set_map_from_log(!a.map_from_log.empty());
  p.set_grid_resolution_m(a.resolution);
  p.set_lenient(a.lenient);
  *spec.mutable_log() = client.Upload(a.log);
  if (a.map.empty()) {
    *spec.mutable_map() = client.Upload(a.map_from_log);
  } else {
    UploadMap(client, a.map, spec);
  }
  if (!a.relations.empty()) *spec.mutable_relations() = client.Upload(a.relations);
  return spec;
}

}  // namespace evoslam::cli
