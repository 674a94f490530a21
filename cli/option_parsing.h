#ifndef EVOSLAM_CLI_OPTION_PARSING_H_
#define EVOSLAM_CLI_OPTION_PARSING_H_

#include <google/protobuf/message.h>

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

#include "common/transform/pose2.h"

namespace evoslam::cli {

// "x,y,theta" (metres, metres, radians); throws Error naming `flag` when malformed.
Pose2 ParsePose(const std::string& text, const std::string& flag);

// Sets the field `name` of `message` from text, a repeated field from comma-separated values,
// replacing what it held. Numbers must be finite; a bool is true, false, 1 or 0. Throws Error
// saying what is wrong when there is no such field or the text does not fit it (a message for
// the caller to prefix with the flag).
void SetField(google::protobuf::Message& message, const std::string& name, std::string_view text);

// CLI11's PositiveNumber and NonNegativeNumber, with messages a person can read (theirs quote
// the largest double).
CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_OPTION_PARSING_H_
