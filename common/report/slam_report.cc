#include "common/report/slam_report.h"

#include <algorithm>
#include <cstdint>
#include <sstream>

#include "common/eval/trajectory_errors.h"
#include "common/io/text_fields.h"
#include "common/slam/methods/slam_methods.h"
#include "common/slam/slam_proto.h"
#include "common/util/counted.h"
#include "common/util/error.h"

namespace evoslam {

std::vector<StampedPose> ScanOdometry(const Dataset& dataset, std::size_t scans) {
  std::vector<StampedPose> odometry;
  odometry.reserve(scans);
  for (std::size_t i = 0; i < scans; ++i) {
    const LaserScan& s = dataset.scans.at(i);
    odometry.push_back({s.timestamp, s.odometry});
  }
  return odometry;
}

proto::SlamReport MakeSlamReport(const Dataset& dataset, const proto::SlamParams& params,
                                 const SlamResult& result,
                                 const std::optional<NamedRelations>& relations,
                                 std::uint32_t threads) {
  const std::size_t n = result.trajectory.size();
  if (n > dataset.scans.size()) {
    throw Error("SLAM report: " + std::to_string(n) + " poses for the " +
                std::to_string(dataset.scans.size()) + " scans of " + dataset.source);
  }
  proto::SlamReport report = result.method_report;
  report.set_format_version(2);
  report.set_evoslam_version(kEvoslamVersion);
  *report.mutable_params() = CompleteSlamParams(params);
  report.set_scans(static_cast<std::uint32_t>(n));
  report.set_seconds(result.seconds);
  report.set_evaluations(result.evaluations);
  report.set_scans_per_second(result.seconds > 0 ? n / result.seconds : 0.0);
  report.set_threads(threads);
  for (const LoopClosure& loop : result.loops) *report.add_loops() = ToProto(loop);
  for (const OdometryStall& stall : result.odometry_stalls) {
    *report.add_odometry_stalls() = ToProto(stall);
  }
  if (n > 0) {
    const auto [earliest, latest] = std::minmax_element(
        dataset.scans.begin(), dataset.scans.begin() + static_cast<std::ptrdiff_t>(n),
        [](const LaserScan& a, const LaserScan& b) { return a.timestamp < b.timestamp; });
    report.set_log_duration_s(latest->timestamp - earliest->timestamp);
  }
  if (auto warnings = LogWarningsOf(dataset, n)) *report.mutable_log_warnings() = *warnings;

  const std::vector<StampedPose> truth = ScanTruth(dataset, n);
  const std::vector<StampedPose> odometry = ScanOdometry(dataset, n);
  if (!truth.empty()) {
    *report.mutable_absolute_errors() = ToProto(ComputeAbsoluteErrors(result.trajectory, truth));
    *report.mutable_odometry_absolute_errors() = ToProto(ComputeAbsoluteErrors(odometry, truth));
  }
  if (auto errors = RelationErrorsReport(result.trajectory, truth, relations)) {
    *report.mutable_relation_errors() = std::move(*errors);
  }
  if (auto errors = RelationErrorsReport(odometry, truth, relations)) {
    *report.mutable_odometry_relation_errors() = std::move(*errors);
  }
  return report;
}

namespace {

void PrintLoops(std::ostream& s, const proto::SlamReport& r) {
  s << "  loops found: " << r.loops_size();
  const char* separator = " (scan ";
  for (const auto& loop : r.loops()) {
    s << separator << loop.later() << " back to " << loop.earlier() << ", score " << loop.score()
      << ", distinctness " << loop.distinctness();
    separator = "; scan ";
  }
  s << (r.loops().empty() ? "\n" : ")\n");
}

}  // namespace

std::string FormatSlamSummary(const proto::SlamReport& r) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  const auto& p = r.params();
  s << "SLAM (" << p.method() << ") over " << r.scans() << " scans of " << p.log() << ", "
    << r.log_duration_s() << " s of log\n";
  s << "  time " << r.seconds() << " s (" << r.scans_per_second() << " scans/s, "
    << Counted(r.threads(), "thread") << ")\n";
  s << FindSlamMethod(p.method()).Summary(r);
  s << FormatOdometryStalls(r.odometry_stalls());
  if (r.has_log_warnings()) s << FormatLogWarnings(r.log_warnings());
  PrintLoops(s, r);
  if (r.has_absolute_errors()) {
    s << "  RMS error vs ground truth: " << FormatAbsoluteErrors(r.absolute_errors())
      << "\n    odometry alone: " << FormatAbsoluteErrors(r.odometry_absolute_errors()) << "\n";
  }
  if (r.has_relation_errors()) {
    const auto& e = r.relation_errors();
    s << "  relative error (" << e.source() << ", " << Counted(e.relations(), "relation")
      << "): " << FormatRelationErrors(e)
      << "\n    odometry alone: " << FormatRelationErrors(r.odometry_relation_errors()) << "\n";
  }
  return s.str();
}

}  // namespace evoslam
