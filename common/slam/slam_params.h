#ifndef EVOSLAM_COMMON_SLAM_SLAM_PARAMS_H_
#define EVOSLAM_COMMON_SLAM_SLAM_PARAMS_H_

#include <google/protobuf/descriptor.h>

#include <string>
#include <string_view>
#include <vector>

#include "evoslam/slam_params.pb.h"

namespace evoslam {

// The SLAM methods the parameters declare: SlamParams' message fields, each named after its
// method, in declaration order.
std::vector<std::string> SlamMethodNames();
// Those names, comma-separated, for messages.
std::string SlamMethodList();

// Throws Error when params.method is no method's, listing those there are, or when the
// parameters of another method than params.method are given.
void CheckOneMethodsParams(const proto::SlamParams& params);

// The same parameters with every field of the top level and of the method's message set to what
// the run uses (a field left unset reads as its declared default): what report.json and
// --print-params show. The values are not checked (CompleteSlamParams does).
proto::SlamParams WithDefaults(const proto::SlamParams& params);

// Sets the parameter `name` from its text form (a number, true/false, or a string): a dotted
// path within the method's message (local.particles for rss.local.particles) or from the top
// (seed, rss.local.particles). Throws Error naming the parameter when no field has that name or
// the text is not a value of its type.
void SetSlamParam(proto::SlamParams& params, std::string_view name, std::string_view text);

// The field of the parameter at the dotted path `name` from the top (rss.local.particles).
// Throws Error when no field has that name.
const google::protobuf::FieldDescriptor& SlamParamField(std::string_view name);

// The value of the parameter at the dotted path `name` from the top (rss.local.particles), in
// text format. Throws Error when no field has that name.
std::string SlamParamText(const proto::SlamParams& params, std::string_view name);

// Reads a text-format parameter file, as --print-params writes one. Throws Error naming the file
// and the line of the first thing it cannot read.
proto::SlamParams ReadSlamParamsFile(const std::string& path);

// The parameters in text format, every field on a line of its own.
std::string SlamParamsText(const proto::SlamParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_SLAM_PARAMS_H_
