#ifndef EVOSLAM_COMMON_UTIL_PROGRAM_OPTIONS_H_
#define EVOSLAM_COMMON_UTIL_PROGRAM_OPTIONS_H_

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

namespace evoslam {

// What the service programs (evoslam-coordinator, evoslam-worker) share on their command line:
// --log-level, and the exit status of a bad command line (2, as for `evoslam`).
inline void AddLogLevelOption(CLI::App& app, std::string& level) {
  app.add_option("--log-level", level, "trace, debug, info, warn, error")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
}

// The log's line pattern. On a terminal each line first clears the one it lands on, so that a
// progress bar drawn there (ProgressBar) gives way to the message rather than running into it;
// the bar is drawn again below on its next update.
inline std::string LogPattern(bool terminal) {
  return std::string(terminal ? "\r\033[K" : "") + "[%H:%M:%S.%e] [%^%l%$] %v";
}

// Sends the program's log to stderr, so that stdout carries only what it is asked for.
inline void LogToStderr(const std::string& program) {
  auto logger = spdlog::stderr_color_mt(program);
  logger->set_pattern(LogPattern(isatty(STDERR_FILENO) != 0));
  spdlog::set_default_logger(std::move(logger));
}

// Parses the command line, logs to stderr and sets the log level. Returns the status to exit with
// at once (0 after --help, 2 for a bad command line), or nullopt to go on.
inline std::optional<int> ParseProgramOptions(CLI::App& app, int argc, char** argv,
                                              const std::string& level) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  LogToStderr(std::filesystem::path(argv[0]).filename().string());
  spdlog::set_level(spdlog::level::from_str(level));
  return std::nullopt;
}

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_PROGRAM_OPTIONS_H_
