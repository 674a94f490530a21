#ifndef EVOSLAM_CLI_OPTION_PARSING_H_
#define EVOSLAM_CLI_OPTION_PARSING_H_

#include <string>

#include "common/transform/pose2.h"

namespace evoslam::cli {

// "x,y,theta" (metres, metres, radians); throws Error naming `flag` when malformed.
Pose2 ParsePose(const std::string& text, const std::string& flag);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_OPTION_PARSING_H_
