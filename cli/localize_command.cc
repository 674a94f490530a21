#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <numbers>
#include <set>
#include <string>

#include "cli/commands.h"
#include "cli/embedded_service.h"
#include "cli/job_client.h"
#include "cli/option_parsing.h"
#include "cli/service_options.h"
#include "common/engine/presets.h"
#include "common/localization/localize_params.h"
#include "common/localization/localizer.h"
#include "common/service/service_client.h"
#include "common/util/error.h"

namespace evoslam::cli {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct LocalizeArgs {
  std::string map, map_from_log, log, out, start, relations;
  std::string fitness = "f3", estimator = "2d", optimizer = "de", strategy = "rand1exp";
  std::size_t pop = 25, gen = 25, max_scans = 0;
  double f = 0.6, cr = 0.9, window = 0.6, heading_window = 30.0, heading_step = 0.5;
  PsoParams pso;
  std::string pso_neighbourhood = "global";
  std::string crossover = "two-point";
  double ga_grid = 0.01, ga_bit_flip = 0.0;
  std::size_t islands = 4, migration_interval = 5, migrants = 1;
  std::string island_algorithm = "de", topology = "ring", migration_policy = "best-replace-worst";
  std::string preset;
  std::set<std::string> given;  // options set on the command line, which override a preset
  double exhaustive_step = 0.01, max_range = 0.0, grid_resolution = 0.05;
  std::uint64_t seed = 1;
  bool use_odometry = false, lenient = false, detach = false;
  int threads = 0;
  std::size_t workers = 0;
  ServiceArgs service;
};

// The job's options from the command line. Values the parser could not check alone (the DE
// strategy, the start pose, parameters that only make sense together) are refused here as
// command-line errors, before any file is read.
LocalizeOptions OptionsFrom(const LocalizeArgs& a) try {
  if (a.map.empty() == a.map_from_log.empty()) {
    throw Error("localize needs exactly one of --map MAP and --map-from-log LOG");
  }
  LocalizeOptions options;
  EstimatorParams& e = options.estimator;
  e.fitness.kind = ParseFitnessKind(a.fitness);
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
  if (use("--pop")) {
    s.de.population = s.jde.population = s.pso.particles = s.ga.population = a.pop;
    // The multi-objective EAs keep their papers' proportions: lambda = 7 mu (002), and four
    // recombinations to one mutation.
    s.mu_plus_lambda.mu = a.pop;
    s.mu_plus_lambda.lambda = 7 * a.pop;
    s.immune.population = a.pop;
    s.immune.recombinations = a.pop - a.pop / 5;
    s.immune.mutations = a.pop / 5;
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
  if (use("--gen")) e.generations = a.gen;
  e.islands = a.islands;
  e.migration.interval = a.migration_interval;
  e.migration.migrants = a.migrants;
  e.migration.topology = ParseTopology(a.topology);
  e.migration.policy = ParseMigrationPolicy(a.migration_policy);
  e.window = a.window;
  e.heading_half_window = a.heading_window * kDeg;
  e.heading_step = a.heading_step * kDeg;
  e.exhaustive_step = a.exhaustive_step;
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

// The job the command line describes, its datasets uploaded through `client`.
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
  p.set_grid_resolution_m(a.grid_resolution);
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
  std::unique_ptr<zmq::context_t> own_context;
  std::unique_ptr<EmbeddedService> embedded;
  std::unique_ptr<ServiceClient> client;
  if (a.service.coordinator.empty()) {
    const EmbeddedLayout layout = ChooseEmbeddedLayout(
        options.estimator.optimizer == OptimizerKind::kIsland ? options.estimator.islands : 1,
        a.workers, a.threads);
    spdlog::debug("embedded: {} workers of {} threads", layout.workers, layout.threads);
    embedded = std::make_unique<EmbeddedService>(layout.workers, layout.threads);
    client = std::make_unique<ServiceClient>(embedded->context(), embedded->client_options());
  } else {
    own_context = std::make_unique<zmq::context_t>();
    client = std::make_unique<ServiceClient>(*own_context, ClientOptionsFrom(a.service));
  }

  const proto::JobSpec spec = JobFrom(a, options, *client);
  const std::string job_id = client->Submit(spec);
  if (a.detach) {
    std::printf("%s\n", job_id.c_str());
    return;
  }
  spdlog::info("{}: localizing with {} / {} / {}", job_id, a.fitness, a.estimator,
               spec.localize().optimizer());
  const std::vector<proto::ResultFile> files = FollowToResult(*client, job_id);
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
  cmd->add_option("--map", a->map, "known map: LineMap text file or map_server .yaml");
  cmd->add_option("--map-from-log", a->map_from_log,
                  "build an occupancy grid from this log's reference poses instead");
  cmd->add_option("--grid-resolution", a->grid_resolution, "cell size for --map-from-log, m")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--log", a->log, "CARMEN log to localize")->required();
  cmd->add_option("--start", a->start,
                  "start pose x,y,theta (m, m, rad); default: first scan's pose");
  cmd->add_flag("--use-odometry", a->use_odometry, "centre the window on the odometry prediction");
  cmd->add_option("--fitness", a->fitness, "f3 (L1 sum) or f2 (beams within tolerance)")
      ->check(CLI::IsMember({"f3", "f2"}));
  cmd->add_option("--estimator", a->estimator, "2d (heading by brute force) or 3d")
      ->check(CLI::IsMember({"2d", "3d"}));
  cmd->add_option("--optimizer", a->optimizer,
                  "an engine algorithm (de, jde, pso, ...), island (an island model of "
                  "--island-algorithm) or exhaustive")
      ->check(CLI::IsMember(OptimizerNames()));
  cmd->add_option("--preset", a->preset,
                  "start from a paper's algorithm, settings and generation count (see "
                  "docs/engine.md); options given as well override them")
      ->check(CLI::IsMember(PresetNames()));
  cmd->add_option("--strategy", a->strategy, "DE strategy, e.g. rand1exp, best1bin");
  cmd->add_option("--pop", a->pop, "population, or particles (PSO); per island with islands")
      ->check(CLI::Range(2, 100000));
  cmd->add_option("--gen", a->gen, "generations")->check(CLI::Range(1, 1000000));
  cmd->add_option("--F", a->f, "DE differential weight")->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--CR", a->cr, "DE crossover rate")->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--w", a->pso.inertia, "PSO inertia weight")->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--c1", a->pso.c1, "PSO pull towards each particle's best")
      ->check(CLI::Range(0.0, 4.0));
  cmd->add_option("--c2", a->pso.c2, "PSO pull towards the swarm's best")
      ->check(CLI::Range(0.0, 4.0));
  cmd->add_option("--vmax", a->pso.vmax_fraction,
                  "PSO velocity clamp per coordinate, as a fraction of the window")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--pso-neighbourhood", a->pso_neighbourhood,
                  "PSO: follow the swarm's best (global) or the best of two ring neighbours")
      ->check(CLI::IsMember({"global", "ring"}));
  cmd->add_option("--crossover", a->crossover, "SGA and aGA: two-point or uniform crossover")
      ->check(CLI::IsMember({"two-point", "uniform"}));
  cmd->add_option("--ga-grid", a->ga_grid,
                  "SGA and aGA: search grid of the binary chromosomes, m (0: none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--ga-bit-flip", a->ga_bit_flip,
                  "SGA and aGA: probability of flipping each bit of a child (003: 0)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--islands", a->islands, "--optimizer island: number of islands")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--island-algorithm", a->island_algorithm,
                  "--optimizer island: the algorithm every island runs")
      ->check(CLI::IsMember(AlgorithmKindNames()));
  cmd->add_option("--migration-interval", a->migration_interval,
                  "--optimizer island: generations between migrations")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--migrants", a->migrants, "--optimizer island: migrants per island")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--topology", a->topology, "--optimizer island: who sends migrants to whom")
      ->check(CLI::IsMember({"ring", "bidirectional-ring", "fully-connected", "star", "random"}));
  cmd->add_option("--migration-policy", a->migration_policy,
                  "--optimizer island: which individuals leave and which they replace")
      ->check(CLI::IsMember({"best-replace-worst", "random-replace"}));
  cmd->add_option("--window", a->window, "side of the square search window, m")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--heading-window", a->heading_window, "heading search half-width, degrees")
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_option("--heading-step", a->heading_step, "heading step, degrees")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--exhaustive-step", a->exhaustive_step,
                  "lattice spacing of --optimizer exhaustive, m")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-range", a->max_range, "simulation range limit, m (default: the scan's)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-scans", a->max_scans, "localize only the first N scans");
  cmd->add_option("--relations", a->relations, "relations file for the relative error");
  cmd->add_option("--seed", a->seed, "random seed");
  cmd->add_option("--threads", a->threads,
                  "embedded: threads per worker (default: the cores shared among the workers)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--workers", a->workers,
                  "embedded: workers in this process (default: one per island, at most one "
                  "per core)")
      ->check(CLI::Range(1, 1024));
  AddServiceOptions(cmd, a->service, true);
  cmd->add_flag("--detach", a->detach, "with --coordinator: print the job id and return at once");
  cmd->add_flag("--lenient", a->lenient, "skip malformed log lines");
  cmd->add_option("--out", a->out, "output directory");
  cmd->callback([a, cmd] {
    for (const CLI::Option* option : cmd->get_options()) {
      if (option->count() > 0) a->given.insert(option->get_name());
    }
    if (a->out.empty() && !a->detach) throw CLI::RequiredError("--out");
    Run(*a);
  });
}

}  // namespace evoslam::cli
