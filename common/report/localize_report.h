#ifndef EVOSLAM_COMMON_REPORT_LOCALIZE_REPORT_H_
#define EVOSLAM_COMMON_REPORT_LOCALIZE_REPORT_H_

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/eval/trajectory_errors.h"
#include "evoslam/localize.pb.h"

namespace evoslam {

proto::AbsoluteErrors ToProto(const AbsoluteErrors& errors);
proto::RelationErrors ToProto(const RelationErrors& errors, const std::string& source);

// Writes a message as indented JSON (all fields, including zeros); throws Error on failure.
void WriteJson(const google::protobuf::Message& message, const std::filesystem::path& path);

// The few lines a person reads first: what ran, how fast, how accurate.
std::string FormatSummary(const proto::LocalizeReport& report);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_LOCALIZE_REPORT_H_
