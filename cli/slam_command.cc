#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "cli/job_run.h"
#include "cli/option_parsing.h"
#include "cli/service_session.h"
#include "common/engine/presets.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/global_search_problem.h"
#include "common/slam/local_search.h"
#include "common/slam/slam_params.h"
#include "common/util/error.h"

namespace evoslam::cli {
namespace {

namespace fs = std::filesystem;

// With neither --log nor --world, SLAM maps this world.
constexpr const char* kDefaultWorld = "office-cluster";

// The drive --world simulates: a 181-beam laser (1 degree over 180, 8 m) with 2 cm of range
// noise, and odometry whose heading drifts by 0.02 rad per metre besides the default noise: on
// office-cluster's 235 m route odometry alone ends up metres from the truth, and the route comes
// back to places it passed (each office's doorway, the hallway) for SLAM to close loops.
SimulationOptions WorldDrive(std::uint64_t seed, std::size_t scans) {
  SimulationOptions o;
  o.laser.beams = 181;
  o.noise.gaussian_sigma = 0.02;
  o.noise.odometry.rotation_bias = 0.02;
  o.max_scans = scans;
  o.seed = seed;
  return o;
}

struct SlamArgs {
  std::string log, world, relations, config;
  proto::SlamParams params;          // the parameters given by their flags; the rest are unset
  std::vector<std::string> assigns;  // --param NAME=VALUE
  bool print_params = false;
  JobRunArgs run;
};

// The parameter's type as CLI11 names an option's value.
std::string TypeName(const std::string& default_text) {
  if (default_text.starts_with('"')) return "TEXT";
  return default_text.find_first_not_of("0123456789") == std::string::npos ? "UINT" : "FLOAT";
}

// A flag that sets the SLAM parameter `name` (a dotted path from the top), which stays unset (at
// its default) without it. Its value is checked against the parameter's type here, and against
// the rest by ParamsFrom.
CLI::Option* AddParamOption(CLI::App* cmd, proto::SlamParams& params, const std::string& flag,
                            const std::string& name, const std::string& help) {
  const std::string value = SlamParamText(CompleteSlamParams({}), name);
  return cmd
      ->add_option_function<std::string>(
          flag,
          [&params, flag, name](const std::string& text) {
            try {
              SetSlamParam(params, name, text);
            } catch (const Error& e) {
              throw CLI::ValidationError(flag, e.what());
            }
          },
          help + " (default " + value + ")")
      ->type_name(TypeName(value));
}

// The flags of the SLAM parameters users tune most; --param and --config reach every one.
void AddSlamParamOptions(CLI::App* cmd, SlamArgs& a) {
  proto::SlamParams& p = a.params;
  AddParamOption(cmd, p, "--method", "method", "SLAM method: rss, paper 002's reduced search space")
      ->check(CLI::IsMember(SlamMethodNames()));
  AddParamOption(cmd, p, "--seed", "seed", "random seed, of the simulation too");
  AddParamOption(cmd, p, "--max-scans", "max_scans",
                 "map only the first N scans, 0: all (with --world, simulate only those)");
  cmd->add_flag_function(
      "--lenient", [&p](std::int64_t) { p.set_lenient(true); },
      "skip malformed log lines and report how many");
  AddParamOption(cmd, p, "--local-fitness", "rss.local.fitness",
                 "local search fitness: eval1 (occupied cells, eq. 1) or eval2 (observations per "
                 "occupied cell, eq. 2)")
      ->check(CLI::IsMember({"eval1", "eval2"}));
  AddParamOption(cmd, p, "--particles", "rss.local.particles", "local search: PSO particles")
      ->check(CLI::Range(std::size_t{2}, kMaxLocalParticles));
  AddParamOption(cmd, p, "--local-iterations", "rss.local.iterations",
                 "local search: PSO iterations per scan")
      ->check(CLI::Range(std::size_t{1}, kMaxLocalIterations));
  AddParamOption(cmd, p, "--resolution", "rss.map.cell_size_m", "map cell size, m")
      ->check(PositiveNumber());
  cmd->add_flag_function(
      "--local-only", [&p](std::int64_t) { SetSlamParam(p, "rss.global.enabled", "false"); },
      "local search alone: no loop detection, no global search");
  AddParamOption(cmd, p, "--global-every", "rss.global.every_scans",
                 "K: a global search every K scans besides those on loops (0: on loops only)");
  AddParamOption(cmd, p, "--partitions", "rss.global.partitions",
                 "L: partitions of a global search's stretch")
      ->check(CLI::Range(std::size_t{1}, kMaxPartitions));
  AddParamOption(cmd, p, "--generations", "rss.global.generations",
                 "generations of each global search")
      ->check(CLI::Range(1, 1000000));
  AddParamOption(cmd, p, "--islands", "rss.global.islands", "islands of each global search")
      ->check(CLI::Range(1, 4096));
  AddParamOption(cmd, p, "--preset", "rss.global.preset",
                 "the algorithm each island runs, as a paper's preset (docs/engine.md)")
      ->check(CLI::IsMember(PresetNames()));
  AddParamOption(cmd, p, "--max-stretch", "rss.global.max_stretch_scans",
                 "scans a global search covers at most (0: the whole loop, or all since the last)");
  AddParamOption(cmd, p, "--loop-radius", "rss.loops.revisit_radius_m",
                 "loop detection: distance from an earlier pose that counts as a revisit, m")
      ->check(PositiveNumber());
  AddParamOption(cmd, p, "--min-match-score", "rss.loops.min_match_score",
                 "loop detection: the fraction of a scan's returns that must match the earlier "
                 "place, (0, 1]")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--param", a.assigns,
                  "NAME=VALUE: any SLAM parameter by its dotted name (docs/configuration.md), the "
                  "method's prefix optional, e.g. local.particles=20; applied after the flags")
      ->type_name("NAME=VALUE");
  cmd->add_option("--config", a.config,
                  "a text-format parameter file, as --print-params writes one; the flags and "
                  "--param apply on top of it")
      ->type_name("FILE");
  cmd->add_flag("--print-params", a.print_params,
                "print every SLAM parameter as the run would use it, in the form --config reads, "
                "and exit");
}

// The parameters the command line gives, the log named as `log`. Values the parser could not
// check alone are refused as command-line errors, before any file is written.
proto::SlamParams ParamsFrom(const SlamArgs& a, const std::string& log) try {
  proto::SlamParams params;
  if (!a.config.empty()) params = ReadSlamParamsFile(a.config);
  params.MergeFrom(a.params);
  for (const std::string& assign : a.assigns) {
    const std::size_t eq = assign.find('=');
    if (eq == std::string::npos) throw Error("--param: expected NAME=VALUE, got '" + assign + "'");
    try {
      SetSlamParam(params, std::string_view(assign).substr(0, eq),
                   std::string_view(assign).substr(eq + 1));
    } catch (const Error& e) {
      throw Error("--param " + assign + ": " + e.what());
    }
  }
  CompleteSlamParams(params);  // throws Error naming the first bad parameter
  params.set_log(log);
  return params;
} catch (const Error& e) {
  throw CLI::ValidationError(e.what());
}

void Run(const SlamArgs& a) {
  const std::string world = !a.log.empty() ? "" : !a.world.empty() ? a.world : kDefaultWorld;
  const std::string log = world.empty() ? a.log : (fs::path(a.run.out) / "log.clf").string();
  const proto::SlamParams params = ParamsFrom(a, log);
  const proto::SlamParams complete = CompleteSlamParams(params);
  if (a.print_params) {
    proto::SlamParams printed = complete;
    printed.clear_log();
    std::printf("%s", SlamParamsText(printed).c_str());
    return;
  }
  CheckJobRunArgs(a.run);
  if (!world.empty() && a.run.out.empty()) {
    throw CLI::ValidationError("--world writes the log it simulates into --out: give --out");
  }

  if (!world.empty()) {
    const World w = BuiltinWorld(world);
    const Dataset dataset = Simulate(w, WorldDrive(complete.seed(), complete.max_scans()));
    WriteSimulation(dataset, w, a.run.out);
    // On stderr with the job's progress: with --detach, stdout is the job id alone.
    spdlog::info("simulated {} scans of {} into {}/{{log.clf,world.lines,truth.txt}}",
                 dataset.scans.size(), w.name, a.run.out);
  }

  ServiceSession session(a.run.service,
                         ChooseEmbeddedLayout(complete.rss().global().enabled()
                                                  ? complete.rss().global().islands()
                                                  : 1,
                                              a.run.workers, a.run.threads));
  ServiceClient& client = session.client();
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_SLAM);
  *spec.mutable_slam() = params;
  *spec.mutable_log() = client.Upload(log);
  if (!a.relations.empty()) *spec.mutable_relations() = client.Upload(a.relations);
  RunJob(client, spec, a.run, "SLAM (" + complete.method() + ") of " + log);
  if (!a.run.detach) {
    std::printf("  map with trajectory: %s\n",
                (fs::path(a.run.out) / "map_trajectory.png").string().c_str());
  }
}

}  // namespace

void AddSlamCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "slam", "Build a map and the trajectory from a log (paper 002's reduced-search-space SLAM)");
  auto a = std::make_shared<SlamArgs>();
  auto* log = cmd->add_option("--log", a->log, "CARMEN log to map");
  cmd->add_option("--world", a->world,
                  fmt::format("simulate a drive with drifting odometry through this built-in "
                              "world into --out and map it (default without --log: {})",
                              kDefaultWorld))
      ->check(CLI::IsMember(BuiltinWorldNames()))
      ->excludes(log);
  cmd->add_option("--relations", a->relations, "relations file for the relative error");
  AddSlamParamOptions(cmd, *a);
  AddJobRunOptions(cmd, a->run);
  AddJobOutputOptions(cmd, a->run);
  cmd->callback([a] { Run(*a); });
}

}  // namespace evoslam::cli
