#include <fmt/format.h>
#include <google/protobuf/text_format.h>
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
  std::string log, world, relations;
  proto::SlamParams params;          // the parameters given by their flags; the rest are unset
  std::vector<std::string> assigns;  // --param NAME=VALUE
  bool print_params = false;
  JobRunArgs run;
};

// The field's type as CLI11 names an option's value.
std::string TypeName(const google::protobuf::FieldDescriptor& field) {
  switch (field.cpp_type()) {
    case google::protobuf::FieldDescriptor::CPPTYPE_DOUBLE:
      return "FLOAT";
    case google::protobuf::FieldDescriptor::CPPTYPE_STRING:
      return "TEXT";
    default:
      return "UINT";
  }
}

// A flag that sets the SlamParams field `field`, which stays unset (at its default) without it.
// Its value is checked against the field's type here, and against the rest by ParamsFrom.
CLI::Option* AddParamOption(CLI::App* cmd, proto::SlamParams& params, const std::string& flag,
                            const std::string& field, const std::string& help) {
  const proto::SlamParams defaults = CompleteSlamParams({});
  const auto* descriptor = defaults.GetDescriptor()->FindFieldByName(field);
  std::string value;
  google::protobuf::TextFormat::PrintFieldValueToString(defaults, descriptor, -1, &value);
  return cmd
      ->add_option_function<std::string>(
          flag,
          [&params, flag, field](const std::string& text) {
            try {
              SetField(params, field, text);
            } catch (const Error& e) {
              throw CLI::ValidationError(flag, e.what());
            }
          },
          help + " (default " + value + ")")
      ->type_name(TypeName(*descriptor));
}

// The flags of the SLAM parameters users tune.
void AddSlamParamOptions(CLI::App* cmd, SlamArgs& a) {
  proto::SlamParams& p = a.params;
  AddParamOption(cmd, p, "--method", "method", "SLAM method: rss, paper 002's reduced search space")
      ->check(CLI::IsMember({"rss"}));
  AddParamOption(cmd, p, "--seed", "seed", "random seed, of the simulation too");
  AddParamOption(cmd, p, "--max-scans", "max_scans",
                 "map only the first N scans, 0: all (with --world, simulate only those)");
  cmd->add_flag_function(
      "--lenient", [&p](std::int64_t) { p.set_lenient(true); },
      "skip malformed log lines and report how many");
  AddParamOption(cmd, p, "--local-fitness", "local_fitness",
                 "local search fitness: eval1 (occupied cells, eq. 1) or eval2 (observations per "
                 "occupied cell, eq. 2)")
      ->check(CLI::IsMember({"eval1", "eval2"}));
  AddParamOption(cmd, p, "--particles", "local_particles", "local search: PSO particles")
      ->check(CLI::Range(std::size_t{2}, kMaxLocalParticles));
  AddParamOption(cmd, p, "--local-iterations", "local_iterations",
                 "local search: PSO iterations per scan")
      ->check(CLI::Range(std::size_t{1}, kMaxLocalIterations));
  AddParamOption(cmd, p, "--resolution", "resolution_m", "map cell size, m")
      ->check(PositiveNumber());
  cmd->add_flag_function(
      "--local-only", [&p](std::int64_t) { p.set_local_only(true); },
      "local search alone: no loop detection, no global search");
  AddParamOption(cmd, p, "--global-every", "global_every",
                 "K: a global search every K scans besides those on loops (0: on loops only)");
  AddParamOption(cmd, p, "--partitions", "partitions", "L: partitions of a global search's stretch")
      ->check(CLI::Range(std::size_t{1}, kMaxPartitions));
  AddParamOption(cmd, p, "--generations", "generations", "generations of each global search")
      ->check(CLI::Range(1, 1000000));
  AddParamOption(cmd, p, "--islands", "islands", "islands of each global search")
      ->check(CLI::Range(1, 4096));
  AddParamOption(cmd, p, "--preset", "preset",
                 "the algorithm each island runs, as a paper's preset (docs/engine.md)")
      ->check(CLI::IsMember(PresetNames()));
  AddParamOption(cmd, p, "--max-stretch", "max_stretch",
                 "scans a global search covers at most (0: the whole loop, or all since the last)");
  AddParamOption(cmd, p, "--loop-radius", "revisit_radius_m",
                 "loop detection: distance from an earlier pose that counts as a revisit, m")
      ->check(PositiveNumber());
  AddParamOption(cmd, p, "--min-match-score", "min_match_score",
                 "loop detection: the fraction of a scan's returns that must match the earlier "
                 "place, (0, 1]")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--param", a.assigns,
                  "NAME=VALUE: any SLAM parameter by its name in proto/evoslam/slam.proto (a list "
                  "comma-separated), e.g. sigma=0.2,0.2,0.2; applied after the flags above");
  cmd->add_flag("--print-params", a.print_params,
                "print every SLAM parameter as the run would use it, by name, and exit");
}

// The parameters the command line gives, the log named as `log`. Values the parser could not
// check alone are refused as command-line errors, before any file is read or written.
proto::SlamParams ParamsFrom(const SlamArgs& a, const std::string& log) try {
  proto::SlamParams params = a.params;
  for (const std::string& assign : a.assigns) {
    const std::size_t eq = assign.find('=');
    if (eq == std::string::npos) throw Error("--param: expected NAME=VALUE, got '" + assign + "'");
    const std::string name = assign.substr(0, eq);
    if (name == "log") throw Error("--param log: the log is --log or --world");
    try {
      SetField(params, name, std::string_view(assign).substr(eq + 1));
    } catch (const Error& e) {
      throw Error("--param " + assign + ": " + e.what());
    }
  }
  params.set_log(log);
  CompleteSlamParams(params);  // throws Error naming the first bad parameter
  return params;
} catch (const Error& e) {
  throw CLI::ValidationError(e.what());
}

void PrintParams(const proto::SlamParams& complete) {
  google::protobuf::TextFormat::Printer printer;
  printer.SetUseShortRepeatedPrimitives(true);
  std::string text;
  printer.PrintToString(complete, &text);
  std::printf("%s", text.c_str());
}

void Run(const SlamArgs& a) {
  const std::string world = !a.log.empty() ? "" : !a.world.empty() ? a.world : kDefaultWorld;
  const std::string log = world.empty() ? a.log : (fs::path(a.run.out) / "log.clf").string();
  const proto::SlamParams params = ParamsFrom(a, log);
  const proto::SlamParams complete = CompleteSlamParams(params);
  if (a.print_params) {
    PrintParams(complete);
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
                         ChooseEmbeddedLayout(complete.local_only() ? 1 : complete.islands(),
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
