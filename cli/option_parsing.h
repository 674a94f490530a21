#ifndef EVOSLAM_CLI_OPTION_PARSING_H_
#define EVOSLAM_CLI_OPTION_PARSING_H_

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "common/transform/pose2.h"

namespace evoslam::cli {

// "x,y,theta" (metres, metres, radians); throws Error naming `flag` when malformed.
Pose2 ParsePose(const std::string& text, const std::string& flag);

// CLI11's PositiveNumber and NonNegativeNumber, with messages a person can read (theirs quote
// the largest double).
CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();
// One of `names`: anything else is refused with the names listed, and the nearest one as a hint
// when it is close ("did you mean 'office-cluster'?").
CLI::Validator OneOf(std::vector<std::string> names);

// Refuses, as a command-line error naming `flag`, an output folder that a run could not write
// into: one that is a file, or whose nearest existing folder is not writable. Creates nothing, so
// that a refused command leaves no trace.
void CheckOutputFolder(const std::string& flag, const std::string& folder);

// Adds the input log to `cmd` as one option with two spellings: the positional `positional` and
// --log; `log` receives it. Both may be given if they name the same file; two different files are
// refused as a command-line error that names both spellings.
CLI::Option* AddLogOption(CLI::App* cmd, const std::string& positional, std::string& log,
                          const std::string& help);

// Adds `old_name` to `cmd` as a deprecated spelling of `option` (which takes a value), hidden from
// --help: its value goes to `option` as if given there, and the run warns that `old_name` is
// deprecated (WarnDeprecatedNames).
void AddDeprecatedName(CLI::App* cmd, const std::string& old_name, CLI::Option* option);

// Logs a warning for each deprecated name the command line used, in `app` and the subcommands it
// ran. main calls it once logging is set up, so that --log-level applies.
void WarnDeprecatedNames(const CLI::App& app);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_OPTION_PARSING_H_
