#include <spdlog/cfg/helpers.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "cli/commands.h"
#include "common/util/error.h"

int main(int argc, char** argv) {
  CLI::App app{"evoslam: maps and trajectories from 2D laser logs with evolutionary optimisers"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "evoslam 0.1.0");
  app.footer(
      "Start with `evoslam slam --out out/slam`: SLAM on a simulated drive through a built-in "
      "office, no input files needed. `evoslam SUBCOMMAND --help` lists a subcommand's options.");
  std::string level = "info";
  app.add_option("--log-level", level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.parse_complete_callback([&] {
    auto logger = spdlog::stderr_color_mt("evoslam");
    logger->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    spdlog::set_default_logger(logger);
    spdlog::set_level(spdlog::level::from_str(level));
  });

  evoslam::cli::AddInfoCommand(app);
  evoslam::cli::AddSimulateCommand(app);
  evoslam::cli::AddSlamCommand(app);
  evoslam::cli::AddLocalizeCommand(app);
  evoslam::cli::AddEvalCommand(app);
  evoslam::cli::AddPlotCommand(app);
  evoslam::cli::AddKeygenCommand(app);
  evoslam::cli::AddJobCommands(app);
  evoslam::cli::AddTuneCommand(app);

  // Exit status: 0 done, 1 bad input (files, data), 2 bad command line, 70 (EX_SOFTWARE) a bug.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version come through here too, with CLI11's status 0.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const evoslam::Error& e) {
    std::fprintf(stderr, "evoslam: error: %s\n", e.what());
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "evoslam: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evoslam: internal error: %s\n", e.what());
    return 70;
  }
  return 0;
}
