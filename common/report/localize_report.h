#ifndef EVOSLAM_COMMON_REPORT_LOCALIZE_REPORT_H_
#define EVOSLAM_COMMON_REPORT_LOCALIZE_REPORT_H_

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/eval/trajectory_errors.h"
#include "common/io/relations.h"
#include "common/io/trajectory_io.h"
#include "common/sensor/dataset.h"
#include "common/sensor/odometry_stalls.h"
#include "evoslam/localize.pb.h"

namespace evoslam {

// What report.json's evoslam_version says.
inline constexpr char kEvoslamVersion[] = "0.1.0";

struct NamedRelations {
  std::string source;  // the file they came from, for the report
  std::vector<Relation> relations;
};

proto::AbsoluteErrors ToProto(const AbsoluteErrors& errors);
proto::RelationErrors ToProto(const RelationErrors& errors, const std::string& source);
proto::OdometryStallRecord ToProto(const OdometryStall& stall);

// What to warn of in the first `scans` scans of the log: lines skipped, odometry jumps, time
// going back; nullopt when there is nothing.
std::optional<proto::LogWarnings> LogWarningsOf(const Dataset& dataset, std::size_t scans);
// The summary's lines for them, each starting with two spaces.
std::string FormatLogWarnings(const proto::LogWarnings& warnings);

// The true poses of the log's first `scans` scans, stamped with the scans' timestamps; scans
// without one are left out.
std::vector<StampedPose> ScanTruth(const Dataset& dataset, std::size_t scans);

// A trajectory's relative error: against `relations` when given, else against consecutive
// ground-truth poses when there are two or more; nothing to measure against, none.
std::optional<proto::RelationErrors> RelationErrorsReport(
    std::span<const StampedPose> trajectory, std::span<const StampedPose> truth,
    const std::optional<NamedRelations>& relations);

// "x 0.71 cm, y 0.66 cm, heading 0.20 deg (max 2.45 cm); aligned: 0.52 cm", as the summaries
// print it; the last is the RMS translation error once the trajectory is aligned to the truth.
std::string FormatAbsoluteErrors(const proto::AbsoluteErrors& errors);
// "0.0114 +- 0.0073 m, 0.500 +- 0.300 deg", as the summaries print it.
std::string FormatRelationErrors(const proto::RelationErrors& errors);

// "  odometry stalled while the robot moved, filled in by time: scans 321 to 324 (then 0.85 m and
// 49.7 deg), ...\n", as the summaries print it; nothing when there were none.
std::string FormatOdometryStalls(
    const google::protobuf::RepeatedPtrField<proto::OdometryStallRecord>& stalls);

// Writes a message as indented JSON (all fields, including zeros); throws Error on failure.
void WriteJson(const google::protobuf::Message& message, const std::filesystem::path& path);

// The few lines a person reads first: what ran, how fast, how accurate.
std::string FormatSummary(const proto::LocalizeReport& report);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_LOCALIZE_REPORT_H_
