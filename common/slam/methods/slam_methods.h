#ifndef EVOSLAM_COMMON_SLAM_METHODS_SLAM_METHODS_H_
#define EVOSLAM_COMMON_SLAM_METHODS_SLAM_METHODS_H_

#include <string_view>

#include "common/slam/slam_method.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// The method of that name. Throws Error listing the methods there are when none has it.
const SlamMethod& FindSlamMethod(std::string_view name);

// Throws Error naming the first parameter that is out of its range, a method that does not exist
// (with the list of those that do), or another method's parameters.
void ValidateSlamParams(const proto::SlamParams& params);

// The parameters validated, with every field of the top level and of the method's message set to
// what the run uses: what report.json and --print-params show.
proto::SlamParams CompleteSlamParams(const proto::SlamParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_METHODS_SLAM_METHODS_H_
