#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/option_parsing.h"
#include "common/line_map/line_map.h"
#include "common/sim/route_file.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/util/error.h"

namespace evoslam::cli {
namespace {

struct SimulateArgs {
  std::string world = "s-corridor", world_file, route_file, out;
  SimulationOptions options;
  bool no_odometry_noise = false;
};

void Run(SimulateArgs a) {
  CheckOutputFolder("--out", a.out);
  World world = a.world_file.empty() ? BuiltinWorld(a.world)
                                     : WorldFromLineMap(ReadLineMap(a.world_file), a.world_file);
  if (!a.route_file.empty()) world.waypoints = ReadRoute(a.route_file);
  if (const double poses = RoutePoseCount(world, a.options); !(poses <= kMaxSimulatedScans)) {
    throw CLI::ValidationError(
        "--step", fmt::format("{} m makes {:.0f} poses of the {} route, more than {:.0f}",
                              a.options.step, poses, world.name, kMaxSimulatedScans));
  }
  if (a.no_odometry_noise) a.options.noise.odometry = {0.0, 0.0, 0.0, 0.0};
  const Dataset log = Simulate(world, a.options);
  WriteSimulation(log, world, a.out);
  std::printf("simulated %zu scans of %s (%zu walls) into %s/{log.clf,world.lines,truth.txt}\n",
              log.scans.size(), world.name.c_str(), world.map.size(), a.out.c_str());
}

}  // namespace

void AddSimulateCommand(CLI::App& app) {
  std::string names;
  for (const auto& n : BuiltinWorldNames()) names += (names.empty() ? "" : ", ") + n;
  auto* cmd = app.add_subcommand("simulate", "Simulate a laser log in a built-in or given world");
  auto a = std::make_shared<SimulateArgs>();
  SimulationOptions& o = a->options;
  auto* world = cmd->add_option("--world", a->world, "built-in world: " + names)
                    ->check(OneOf(BuiltinWorldNames()));
  cmd->add_option("--world-file", a->world_file,
                  "any LineMap file as world (a route through its free space is chosen)")
      ->type_name("FILE")
      ->excludes(world);
  cmd->add_option("--route", a->route_file,
                  "route file, one waypoint \"x y\" (m) per line, to drive instead of the world's")
      ->type_name("FILE");
  cmd->add_option("--beams", o.laser.beams, "laser beams")->check(CLI::Range(2, 100000));
  cmd->add_option("--fov", o.laser.field_of_view_deg, "field of view, degrees")
      ->check(CLI::Range(1.0, 360.0));
  cmd->add_option("--max-range", o.laser.max_range, "laser range, m")->check(PositiveNumber());
  cmd->add_option("--noise-uniform", o.noise.uniform_bandwidth,
                  "additive uniform noise: bandwidth (max - min), m")
      ->check(NonNegativeNumber());
  cmd->add_option("--noise-gaussian", o.noise.gaussian_sigma, "additive Gaussian noise sigma, m")
      ->check(NonNegativeNumber());
  cmd->add_option("--quantization", o.noise.quantization, "range quantization step, m")
      ->check(NonNegativeNumber());
  cmd->add_option("--pedestrians", o.noise.pedestrians, "people walking about, occluding beams")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--odometry-translation-noise", o.noise.odometry.translation_sigma,
                  "relative sigma per increment")
      ->check(NonNegativeNumber());
  cmd->add_option("--odometry-rotation-noise", o.noise.odometry.rotation_sigma,
                  "relative sigma per increment")
      ->check(NonNegativeNumber());
  cmd->add_flag("--perfect-odometry", a->no_odometry_noise, "odometry equal to the true motion");
  cmd->add_option("--step", o.step, "metres between scans (default: the world's)")
      ->check(NonNegativeNumber());
  cmd->add_option("--max-scans", o.max_scans, "stop after N scans (0: whole route)");
  cmd->add_option("--seed", o.seed, "random seed");
  cmd->add_option("--out", a->out, "output folder")->type_name("DIR")->required();
  cmd->callback([a] { Run(*a); });
}

}  // namespace evoslam::cli
