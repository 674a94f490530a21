#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "cli/job_run.h"
#include "cli/option_parsing.h"
#include "cli/service_session.h"
#include "common/io/file_bytes.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/methods/slam_methods.h"
#include "common/slam/slam_params.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

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
std::string TypeName(const google::protobuf::FieldDescriptor& field) {
  switch (field.cpp_type()) {
    case google::protobuf::FieldDescriptor::CPPTYPE_DOUBLE:
      return "FLOAT";
    case google::protobuf::FieldDescriptor::CPPTYPE_STRING:
      return "TEXT";
    case google::protobuf::FieldDescriptor::CPPTYPE_BOOL:
      return "BOOL";
    default:
      return "UINT";
  }
}

// The parameters with `name` set to `text`, checked as a run would check them (the others at
// their defaults); throws Error saying what is wrong.
void CheckParam(const std::string& name, const std::string& text) {
  proto::SlamParams p;
  // A method's own parameter is checked in a run of that method.
  for (const std::string& method : SlamMethodNames()) {
    if (name.starts_with(method + ".")) p.set_method(method);
  }
  SetSlamParam(p, name, text);
  ValidateSlamParams(p);
}

// A flag that sets the SLAM parameter `name` (a dotted path from the top), which stays unset (at
// its default) without it; a switch sets it to `value`. Its value is checked here, so that the
// error names the flag; the parameters together are checked again by ParamsFrom.
void AddParamOption(CLI::App* cmd, proto::SlamParams& params, const SlamFlag& f) {
  const auto set = [&params, f](const std::string& text) {
    try {
      CheckParam(f.param, text);
      SetSlamParam(params, f.param, text);
    } catch (const Error& e) {
      throw CLI::ValidationError(f.flag, e.what());
    }
  };
  if (!f.value.empty()) {
    cmd->add_flag_function(
        f.flag, [set, value = f.value](std::int64_t) { set(value); }, f.help);
    return;
  }
  // The default as --help shows every other option's: "=VALUE", a string without its quotes.
  std::string value = SlamParamText(CompleteSlamParams({}), f.param);
  if (value.size() >= 2 && value.front() == '"') value = value.substr(1, value.size() - 2);
  CLI::Option* option = cmd->add_option_function<std::string>(f.flag, set, f.help)
                            ->type_name(TypeName(SlamParamField(f.param)))
                            ->default_str(value);
  if (!f.deprecated.empty()) AddDeprecatedName(cmd, f.deprecated, option);
}

// The flags of the SLAM parameters users tune most: those of every run, then each method's.
void AddSlamParamOptions(CLI::App* cmd, SlamArgs& a) {
  proto::SlamParams& p = a.params;
  AddParamOption(cmd, p, {"--method", "method", "SLAM method: " + SlamMethodList(), ""});
  AddParamOption(cmd, p, {"--seed", "seed", "random seed, of the simulation too", ""});
  AddParamOption(cmd, p,
                 {"--max-scans", "max_scans",
                  "map only the first N scans, 0: all (with --world, simulate only those)", ""});
  AddParamOption(cmd, p,
                 {"--lenient", "lenient", "skip malformed log lines and report how many", "true"});
  for (const std::string& name : SlamMethodNames()) {
    for (const SlamFlag& f : FindSlamMethod(name).Flags()) AddParamOption(cmd, p, f);
  }
  cmd->add_option("--param", a.assigns,
                  "NAME=VALUE: any SLAM parameter by its dotted name (docs/configuration.md), the "
                  "method's prefix optional, e.g. local.particles=20; applied after the flags")
      ->type_name("NAME=VALUE")
      ->default_str("");
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
  if (!a.print_params) CheckJobRunArgs(a.run);
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
  if (!world.empty() && a.run.out.empty()) {
    throw CLI::ValidationError("--world writes the log it simulates into --out: give --out");
  }

  // The simulated drive is staged and joins --out only once the job is under way, so that a run
  // refused for its parameters leaves nothing behind.
  std::optional<TempDir> staged;
  if (!world.empty()) {
    const World w = BuiltinWorld(world);
    const Dataset dataset = Simulate(w, WorldDrive(complete.seed(), complete.max_scans()));
    staged.emplace("evoslam-world");
    WriteSimulation(dataset, w, staged->path());
    // On stderr with the job's progress: with --detach, stdout is the job id alone.
    spdlog::info("simulated {} scans of {} for {}/{{log.clf,world.lines,truth.txt}}",
                 dataset.scans.size(), w.name, a.run.out);
  }

  ServiceSession session(a.run.service,
                         ChooseEmbeddedLayout(FindSlamMethod(complete.method()).Islands(complete),
                                              a.run.workers, a.run.threads));
  ServiceClient& client = session.client();
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_SLAM);
  *spec.mutable_slam() = params;
  *spec.mutable_log() =
      staged ? client.UploadBytes(log, ReadFileBytes(*staged / "log.clf")) : client.Upload(log);
  if (!a.relations.empty()) *spec.mutable_relations() = client.Upload(a.relations);
  RunJob(client, spec, a.run, "SLAM (" + complete.method() + ") of " + log);
  if (staged) {
    // The run's own files (truth.txt among them) stand; the simulation adds the log and walls.
    fs::create_directories(a.run.out);
    for (const char* name : {"log.clf", "world.lines", "truth.txt"}) {
      const fs::path to = fs::path(a.run.out) / name;
      if (!fs::exists(to)) fs::copy_file(*staged / name, to);
    }
  }
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
  auto* log = AddLogOption(cmd, "log", a->log, "CARMEN log to map");
  cmd->add_option("--world", a->world,
                  fmt::format("simulate a drive with drifting odometry through this built-in "
                              "world into --out and map it (default without --log: {})",
                              kDefaultWorld))
      ->check(OneOf(BuiltinWorldNames()))
      ->excludes(log);
  cmd->add_option("--relations", a->relations, "relations file for the relative error")
      ->type_name("FILE");
  AddSlamParamOptions(cmd, *a);
  AddJobRunOptions(cmd, a->run);
  AddJobOutputOptions(cmd, a->run);
  cmd->callback([a] { Run(*a); });
}

}  // namespace evoslam::cli
