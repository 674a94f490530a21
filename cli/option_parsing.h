#ifndef EVOSLAM_CLI_OPTION_PARSING_H_
#define EVOSLAM_CLI_OPTION_PARSING_H_

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

#include "common/transform/pose2.h"

namespace evoslam::cli {

// "x,y,theta" (metres, metres, radians); throws Error naming `flag` when malformed.
Pose2 ParsePose(const std::string& text, const std::string& flag);

// CLI11's PositiveNumber and NonNegativeNumber, with messages a person can read (theirs quote
// the largest double).
CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();

// Refuses, as a command-line error naming `flag`, an output folder that a run could not write
// into: one that is a file, or whose nearest existing folder is not writable. Creates nothing, so
// that a refused command leaves no trace.
void CheckOutputFolder(const std::string& flag, const std::string& folder);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_OPTION_PARSING_H_
