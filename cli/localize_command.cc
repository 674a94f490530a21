#include <omp.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>
#include <string>

#include "cli/commands.h"
#include "cli/option_parsing.h"
#include "common/engine/engine_proto.h"
#include "common/engine/presets.h"
#include "common/eval/trajectory_errors.h"
#include "common/grid/map_io.h"
#include "common/io/carmen_reader.h"
#include "common/io/relations.h"
#include "common/io/trajectory_io.h"
#include "common/localization/localizer.h"
#include "common/report/localize_report.h"
#include "common/report/map_picture.h"
#include "common/util/error.h"
#include "common/util/progress_bar.h"

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
  bool use_odometry = false, lenient = false;
  int threads = 0;
};

// A grid of the log's reference poses: ground truth where the log has it, else its stated poses.
OccupancyGrid GridFromLog(const std::string& path, double resolution, bool lenient) {
  const Dataset dataset = ReadCarmen(path, {.lenient = lenient});
  std::vector<Pose2> poses;
  for (const LaserScan& s : dataset.scans) poses.push_back(s.true_pose.value_or(s.pose));
  spdlog::info("building a {:.3f} m grid from {} scans of {}", resolution, poses.size(), path);
  return OccupancyGrid::FromScans(dataset.scans, poses, resolution, 1.0);
}

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

void Run(const LocalizeArgs& a) {
  const LocalizeOptions options = OptionsFrom(a);
  if (a.threads > 0) omp_set_num_threads(a.threads);

  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);

  CarmenReadStats stats;
  const Dataset dataset = ReadCarmen(a.log, {.lenient = a.lenient}, &stats);
  if (stats.skipped > 0) {
    spdlog::warn("{}: skipped {} malformed lines (first: {})", a.log, stats.skipped,
                 stats.first_skip_reason);
  }
  const MapModel map = a.map.empty()
                           ? MapModel(GridFromLog(a.map_from_log, a.grid_resolution, a.lenient))
                           : LoadMapModel(a.map);
  std::vector<std::string> outputs;
  if (!a.map_from_log.empty()) {
    WriteMapYaml(*map.grid(), out / "map.yaml");
    outputs.insert(outputs.end(), {"map.yaml", "map.pgm"});
  }

  spdlog::info("localizing {} scans with {} / {} / {}", dataset.scans.size(), a.fitness,
               a.estimator, a.optimizer);
  LocalizeResult result;
  {
    ProgressBar bar("localize", options.max_scans
                                    ? std::min(options.max_scans, dataset.scans.size())
                                    : dataset.scans.size());
    result =
        Localize(map, dataset, options, [&](std::size_t done, std::size_t) { bar.Update(done); });
  }

  WriteTrajectoryText(result.trajectory, out / "trajectory.txt");
  WriteTrajectoryTum(result.trajectory, out / "trajectory.tum");
  outputs.insert(outputs.end(), {"trajectory.txt", "trajectory.tum"});

  proto::LocalizeReport report;
  report.set_format_version(1);
  report.set_evoslam_version("0.1.0");
  auto& p = *report.mutable_params();
  p.set_map(a.map.empty() ? "grid from " + a.map_from_log : a.map);
  p.set_log(a.log);
  p.set_fitness(a.fitness);
  p.set_estimator(a.estimator);
  // The effective settings, after any preset, so the report says what actually ran.
  const EstimatorParams& e = options.estimator;
  p.set_optimizer(e.optimizer == OptimizerKind::kAlgorithm
                      ? std::string(AlgorithmKindName(e.algorithm.kind))
                      : a.optimizer);
  p.set_preset(a.preset);
  p.set_strategy(std::string(DeStrategyName(e.algorithm.de.strategy)));
  p.set_population(static_cast<std::uint32_t>(PopulationSize(e.algorithm)));
  p.set_generations(static_cast<std::uint32_t>(e.generations));
  p.set_f(e.algorithm.de.f);
  p.set_cr(e.algorithm.de.cr);
  p.set_pso_inertia(e.algorithm.pso.inertia);
  p.set_pso_c1(e.algorithm.pso.c1);
  p.set_pso_c2(e.algorithm.pso.c2);
  p.set_pso_vmax_fraction(e.algorithm.pso.vmax_fraction);
  p.set_pso_neighbourhood(std::string(PsoNeighbourhoodName(e.algorithm.pso.neighbourhood)));
  if (e.optimizer != OptimizerKind::kExhaustive) *p.mutable_algorithm() = ToProto(e.algorithm);
  if (e.optimizer == OptimizerKind::kIsland) {
    p.set_islands(static_cast<std::uint32_t>(a.islands));
    p.set_island_algorithm(std::string(AlgorithmKindName(e.algorithm.kind)));
    p.set_migration_interval(static_cast<std::uint32_t>(a.migration_interval));
    p.set_migrants(static_cast<std::uint32_t>(a.migrants));
    p.set_topology(a.topology);
    p.set_migration_policy(a.migration_policy);
  }
  p.set_window_m(a.window);
  p.set_heading_window_deg(a.heading_window);
  p.set_heading_step_deg(a.heading_step);
  p.set_use_odometry(a.use_odometry);
  p.set_seed(a.seed);
  p.set_max_range_m(a.max_range);
  p.set_max_scans(static_cast<std::uint32_t>(a.max_scans));
  if (options.start) {
    for (double v : {options.start->x(), options.start->y(), options.start->theta()})
      p.add_start(v);
  }
  report.set_scans(static_cast<std::uint32_t>(result.trajectory.size()));
  report.set_evaluations(result.evaluations);
  report.set_runtime_s(result.seconds);
  report.set_scans_per_second(result.seconds > 0 ? result.trajectory.size() / result.seconds : 0);
  report.set_threads(static_cast<std::uint32_t>(omp_get_max_threads()));

  std::vector<StampedPose> truth;
  for (std::size_t i = 0; i < result.trajectory.size(); ++i) {
    const LaserScan& s = dataset.scans[i];
    if (s.true_pose) truth.push_back({s.timestamp, *s.true_pose});
  }
  if (!truth.empty()) {
    *report.mutable_absolute_errors() = ToProto(ComputeAbsoluteErrors(result.trajectory, truth));
  }
  if (!a.relations.empty()) {
    *report.mutable_relation_errors() =
        ToProto(ComputeRelationErrors(result.trajectory, ReadRelations(a.relations)), a.relations);
  } else if (truth.size() > 1) {
    *report.mutable_relation_errors() =
        ToProto(ComputeRelationErrors(result.trajectory, RelationsFromTruth(truth)),
                "ground truth, consecutive scans");
  }

  std::vector<TrajectoryLayer> layers;
  if (!truth.empty()) {
    TrajectoryLayer t{"truth", {}, {0, 160, 0}};
    for (const auto& s : truth) t.poses.push_back(s.pose);
    layers.push_back(std::move(t));
  }
  TrajectoryLayer estimated{"estimate", {}, {220, 30, 30}};
  for (const auto& s : result.trajectory) estimated.poses.push_back(s.pose);
  layers.push_back(std::move(estimated));
  WriteMapPicture(map, layers, out / "map.png");
  outputs.insert(outputs.end(), {"map.png", "report.json", "summary.txt"});
  for (const auto& o : outputs) report.add_outputs(o);

  WriteJson(report, out / "report.json");
  const std::string summary = FormatSummary(report);
  std::ofstream(out / "summary.txt") << summary;
  std::printf("%s", summary.c_str());
  std::printf("  wrote %s/{trajectory.txt,trajectory.tum,report.json,summary.txt,map.png}\n",
              a.out.c_str());
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
  cmd->add_option("--threads", a->threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--lenient", a->lenient, "skip malformed log lines");
  cmd->add_option("--out", a->out, "output directory")->required();
  cmd->callback([a, cmd] {
    for (const CLI::Option* option : cmd->get_options()) {
      if (option->count() > 0) a->given.insert(option->get_name());
    }
    Run(*a);
  });
}

}  // namespace evoslam::cli
