#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>
#include <zmq.hpp>

#include "cli/commands.h"
#include "cli/option_parsing.h"
#include "common/util/error.h"
#include "common/util/nearest_name.h"
#include "common/util/program_options.h"

namespace {

// The word where the subcommand should stand when it names none: the first argument that is
// neither an option nor --log-level's value.
std::optional<std::string> UnknownSubcommand(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--log-level") {
      ++i;
      continue;
    }
    if (arg.starts_with("-")) continue;
    for (const CLI::App* sub : app.get_subcommands({})) {
      if (sub->check_name(std::string(arg))) return std::nullopt;
    }
    return std::string(arg);
  }
  return std::nullopt;
}

int RefuseUnknownSubcommand(const CLI::App& app, const std::string& typed) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  std::string message = "evoslam: error: '" + typed + "' is not a subcommand";
  if (const auto nearest = evoslam::NearestName(typed, names)) {
    message += "; did you mean '" + *nearest + "'?";
  } else {
    message += "; `evoslam --help` lists them";
  }
  std::fprintf(stderr, "%s\n", message.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"evoslam: maps and trajectories from 2D laser logs with evolutionary optimisers"};
  app.require_subcommand(1);
  // --log-level may follow the subcommand too.
  app.fallthrough();
  // Every option's --help shows its default.
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", "evoslam 0.1.0");
  app.footer(
      "Start with `evoslam slam --out out/slam`: SLAM on a simulated drive through a built-in "
      "office, no input files needed. `evoslam SUBCOMMAND --help` lists a subcommand's options.");
  std::string level = "info";
  app.add_option("--log-level", level, "trace, debug, info, warn, error or off")
      ->check(evoslam::cli::OneOf({"trace", "debug", "info", "warn", "error", "off"}));
  app.parse_complete_callback([&] {
    evoslam::LogToStderr("evoslam");
    spdlog::set_level(spdlog::level::from_str(level));
    evoslam::cli::WarnDeprecatedNames(app);
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

  if (const auto typed = UnknownSubcommand(app, argc, argv)) {
    return RefuseUnknownSubcommand(app, *typed);
  }

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
  } catch (const zmq::error_t& e) {
    // The host ran out of something sockets need (files, memory), not a fault of the job.
    std::fprintf(stderr, "evoslam: error: ZeroMQ: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evoslam: internal error: %s\n", e.what());
    return 70;
  }
  return 0;
}
