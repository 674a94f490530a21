#include "common/report/localize_report.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "common/io/file_bytes.h"
#include "common/sensor/log_anomalies.h"
#include "common/transform/angle_units.h"
#include "common/util/counted.h"
#include "common/util/error.h"

namespace evoslam {

proto::AbsoluteErrors ToProto(const AbsoluteErrors& e) {
  proto::AbsoluteErrors p;
  p.set_poses(static_cast<std::uint32_t>(e.poses));
  p.set_rms_x_m(e.rms_x);
  p.set_rms_y_m(e.rms_y);
  p.set_rms_theta_deg(Degrees(e.rms_theta));
  p.set_rms_translation_m(e.rms_translation);
  p.set_max_translation_m(e.max_translation);
  p.set_aligned_rms_translation_m(e.aligned_rms_translation);
  p.set_scale_aligned_rms_translation_m(e.scale_aligned_rms_translation);
  p.set_alignment_scale(e.alignment_scale);
  return p;
}

proto::RelationErrors ToProto(const RelationErrors& e, const std::string& source) {
  proto::RelationErrors p;
  p.set_source(source);
  p.set_relations(static_cast<std::uint32_t>(e.relations));
  p.set_skipped(static_cast<std::uint32_t>(e.skipped));
  p.set_translation_mean_m(e.translation_mean);
  p.set_translation_std_m(e.translation_std);
  p.set_rotation_mean_deg(Degrees(e.rotation_mean));
  p.set_rotation_std_deg(Degrees(e.rotation_std));
  p.set_translation_sq_mean_m2(e.translation_sq_mean);
  p.set_translation_sq_std_m2(e.translation_sq_std);
  p.set_rotation_sq_mean_deg2(Degrees(Degrees(e.rotation_sq_mean)));
  p.set_rotation_sq_std_deg2(Degrees(Degrees(e.rotation_sq_std)));
  return p;
}

proto::OdometryStallRecord ToProto(const OdometryStall& stall) {
  proto::OdometryStallRecord p;
  p.set_first(static_cast<std::uint32_t>(stall.first));
  p.set_last(static_cast<std::uint32_t>(stall.last));
  p.set_catch_up_m(stall.catch_up.translation().norm());
  p.set_catch_up_rad(stall.catch_up.theta());
  p.set_position_only(!stall.heading_held);
  return p;
}

std::vector<StampedPose> ScanTruth(const Dataset& dataset, std::size_t scans) {
  std::vector<StampedPose> truth;
  for (std::size_t i = 0; i < scans; ++i) {
    const LaserScan& s = dataset.scans.at(i);
    if (s.true_pose) truth.push_back({s.timestamp, *s.true_pose});
  }
  return truth;
}

std::optional<proto::RelationErrors> RelationErrorsReport(
    std::span<const StampedPose> trajectory, std::span<const StampedPose> truth,
    const std::optional<NamedRelations>& relations) {
  if (relations) {
    return ToProto(ComputeRelationErrors(trajectory, relations->relations), relations->source);
  }
  if (truth.size() < 2) return std::nullopt;
  return ToProto(ComputeRelationErrors(trajectory, RelationsFromTruth(truth)),
                 "ground truth, consecutive scans");
}

std::string FormatAbsoluteErrors(const proto::AbsoluteErrors& a) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "x " << 100 * a.rms_x_m() << " cm, y " << 100 * a.rms_y_m() << " cm, heading "
    << a.rms_theta_deg() << " deg (max " << 100 * a.max_translation_m()
    << " cm); aligned: " << 100 * a.aligned_rms_translation_m() << " cm";
  if (a.alignment_scale() > 0.0) {
    s.precision(4);
    s << "; aligned and scaled (x" << a.alignment_scale() << "): ";
    s.precision(2);
    s << 100 * a.scale_aligned_rms_translation_m() << " cm";
  }
  return s.str();
}

std::string FormatRelationErrors(const proto::RelationErrors& e) {
  // Zeros would read as a perfect score.
  if (e.relations() == 0) {
    return "none of the " + std::to_string(e.skipped()) + " relations joins two scans estimated";
  }
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(4);
  s << e.translation_mean_m() << " +- " << e.translation_std_m() << " m, ";
  s.precision(3);
  s << e.rotation_mean_deg() << " +- " << e.rotation_std_deg() << " deg";
  return s.str();
}

void WriteJson(const google::protobuf::Message& message, const std::filesystem::path& path) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string json;
  const auto status = google::protobuf::util::MessageToJsonString(message, &json, options);
  if (!status.ok()) throw Error(path.string() + ": cannot encode JSON: " + status.ToString());
  WriteFileBytes(path, json);
}

std::optional<proto::LogWarnings> LogWarningsOf(const Dataset& dataset, std::size_t scans) {
  const LogAnomalies anomalies =
      FindLogAnomalies(std::span<const LaserScan>(dataset.scans).first(scans));
  if (dataset.skipped_lines == 0 && anomalies.jumps.empty() && anomalies.reversals.empty()) {
    return std::nullopt;
  }
  proto::LogWarnings w;
  w.set_skipped_lines(dataset.skipped_lines);
  w.set_typical_step_m(anomalies.typical_step_m);
  for (const OdometryJump& jump : anomalies.jumps) {
    proto::OdometryJumpRecord& r = *w.add_odometry_jumps();
    r.set_from(static_cast<std::uint32_t>(jump.from));
    r.set_length_m(jump.length_m);
  }
  for (const TimeReversal& reversal : anomalies.reversals) {
    proto::TimeReversalRecord& r = *w.add_time_reversals();
    r.set_scan(static_cast<std::uint32_t>(reversal.scan));
    r.set_back_s(reversal.back_s);
  }
  return w;
}

std::string FormatLogWarnings(const proto::LogWarnings& w) {
  // Enough of a long list to find the places in the log; the whole list is in report.json.
  constexpr int kListed = 5;
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  if (w.skipped_lines() > 0) {
    s << "  skipped " << Counted(w.skipped_lines(), "malformed line") << " of the log\n";
  }
  if (!w.odometry_jumps().empty()) {
    s << "  odometry jumps (steps far beyond the log's " << w.typical_step_m()
      << " m pace; the map may have a straight line through it):";
    for (int i = 0; i < std::min(kListed, w.odometry_jumps_size()); ++i) {
      const auto& jump = w.odometry_jumps(i);
      s << (i == 0 ? " " : ", ") << jump.length_m() << " m from scan " << jump.from() << " to "
        << jump.from() + 1;
    }
    if (w.odometry_jumps_size() > kListed)
      s << " and " << w.odometry_jumps_size() - kListed << " more";
    s << "\n";
  }
  if (!w.time_reversals().empty()) {
    s << "  timestamps go back " << Counted(w.time_reversals_size(), "time")
      << " (the scans are taken in file order):";
    for (int i = 0; i < std::min(kListed, w.time_reversals_size()); ++i) {
      const auto& reversal = w.time_reversals(i);
      s << (i == 0 ? " " : ", ") << "at scan " << reversal.scan() << " by " << reversal.back_s()
        << " s";
    }
    if (w.time_reversals_size() > kListed)
      s << " and " << w.time_reversals_size() - kListed << " more";
    s << "\n";
  }
  return s.str();
}

std::string FormatOdometryStalls(
    const google::protobuf::RepeatedPtrField<proto::OdometryStallRecord>& stalls) {
  if (stalls.empty()) return {};
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s << "  odometry stalled while the robot moved, filled in by time: scans ";
  const char* separator = "";
  for (const auto& stall : stalls) {
    s << separator << stall.first() << " to " << stall.last() << " ("
      << (stall.position_only() ? "position only, " : "") << "then " << std::setprecision(2)
      << stall.catch_up_m() << " m and " << std::setprecision(1) << Degrees(stall.catch_up_rad())
      << " deg)";
    separator = ", ";
  }
  s << "\n";
  return s.str();
}

std::string FormatSummary(const proto::LocalizeReport& r) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  const auto& p = r.params();
  s.precision(2);
  s << "localized " << r.scans() << " scans of " << p.log() << " in " << p.map() << "\n";
  s << "  " << p.fitness();
  if (p.fitness() == "f2") {
    s << " (within " << std::setprecision(3) << p.f2_base_m() << " m + " << std::setprecision(4)
      << p.f2_slope() << " x the two ranges)" << std::setprecision(2);
  } else if (p.f3_cap_m() > 0.0) {
    s << " (each beam's difference capped at " << std::setprecision(3) << p.f3_cap_m() << " m)"
      << std::setprecision(2);
  }
  s << ", " << p.estimator() << " estimator, " << p.optimizer();
  if (p.optimizer() == "island") {
    s << " of " << p.islands() << " " << p.island_algorithm() << " islands (" << p.topology()
      << ", " << p.migrants() << " migrants every " << p.migration_interval() << " generations)";
  }
  if (p.optimizer() == "de" || (p.optimizer() == "island" && p.island_algorithm() == "de"))
    s << " " << p.strategy();
  if (p.optimizer() != "exhaustive") {
    s << " (population " << p.population() << ", generations " << p.generations() << ")";
  }
  s << ", window " << p.window_m() << " m, heading +-" << p.heading_window_deg() << " deg\n";
  s << "  runtime " << r.runtime_s() << " s (" << r.scans_per_second() << " scans/s, "
    << Counted(r.threads(), "thread") << "), " << r.evaluations() << " fitness evaluations\n";
  if (r.has_absolute_errors()) {
    s << "  RMS error vs ground truth: " << FormatAbsoluteErrors(r.absolute_errors()) << "\n";
  }
  if (r.has_relation_errors()) {
    const auto& e = r.relation_errors();
    s << "  relative error (" << e.source() << ", " << Counted(e.relations(), "relation")
      << "): " << FormatRelationErrors(e) << "\n";
  }
  s << FormatOdometryStalls(r.odometry_stalls());
  if (r.has_log_warnings()) s << FormatLogWarnings(r.log_warnings());
  return s.str();
}

}  // namespace evoslam
