#ifndef EVOSLAM_TESTS_CLI_TESTING_H_
#define EVOSLAM_TESTS_CLI_TESTING_H_

// For the command line's tests: runs a shell command and keeps what it printed.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "common/util/temp_dir.h"

namespace evoslam::testing {

struct CommandResult {
  int status = 0;
  std::string output;  // stdout, and stderr unless it was kept apart
  std::string error;   // stderr, when it was kept apart
};

// Runs `command_line` with sh; `split` keeps stderr apart from stdout.
inline CommandResult RunCommand(const std::string& command_line, bool split = false) {
  const TempDir dir("evoslam-cli-test");
  const std::filesystem::path stderr_file = dir / "stderr";
  const std::string command =
      command_line + (split ? " 2>'" + stderr_file.string() + "'" : std::string(" 2>&1"));
  CommandResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed", ""};
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) r.output += buffer.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  if (split) {
    std::ifstream in(stderr_file);
    r.error.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return r;
}

// This build's evoslam with `args`.
inline CommandResult RunCli(const std::string& args, bool split = false) {
  return RunCommand(std::string(EVOSLAM_CLI) + " " + args, split);
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_TESTS_CLI_TESTING_H_
