#include "common/report/slam_report.h"

#include <cstdint>
#include <sstream>

#include "common/eval/trajectory_errors.h"
#include "common/io/text_fields.h"
#include "common/slam/slam_params.h"
#include "common/util/error.h"

namespace evoslam {

proto::GlobalSearchRecord ToProto(const GlobalSearchRecord& search) {
  proto::GlobalSearchRecord p;
  p.set_first(static_cast<std::uint32_t>(search.first));
  p.set_last(static_cast<std::uint32_t>(search.last));
  p.set_loop(search.loop.has_value());
  p.set_applied(search.applied);
  p.set_evaluations(search.evaluations);
  p.set_seconds(search.seconds);
  for (double v : search.before) p.add_before(v);
  for (double v : search.after) p.add_after(v);
  return p;
}

proto::SlamPhaseTimes ToProto(const SlamPhaseTimes& times) {
  proto::SlamPhaseTimes p;
  p.set_local_s(times.local);
  p.set_detection_s(times.detection);
  p.set_global_s(times.global);
  p.set_total_s(times.total);
  return p;
}

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
                                 const RssSlamResult& result,
                                 const std::optional<NamedRelations>& relations,
                                 std::uint32_t threads) {
  const std::size_t n = result.trajectory.size();
  if (n > dataset.scans.size()) {
    throw Error("SLAM report: " + std::to_string(n) + " poses for the " +
                std::to_string(dataset.scans.size()) + " scans of " + dataset.source);
  }
  proto::SlamReport report;
  report.set_format_version(1);
  report.set_evoslam_version(kEvoslamVersion);
  *report.mutable_params() = CompleteSlamParams(params);
  report.set_scans(static_cast<std::uint32_t>(n));
  report.set_local_evaluations(result.local_evaluations);
  report.set_global_evaluations(result.global_evaluations);
  *report.mutable_times() = ToProto(result.times);
  report.set_scans_per_second(result.times.total > 0 ? n / result.times.total : 0.0);
  report.set_threads(threads);
  for (const LoopClosure& loop : result.loops) *report.add_loops() = ToProto(loop);
  for (const OdometryStall& stall : result.odometry_stalls) {
    *report.add_odometry_stalls() = ToProto(stall);
  }
  for (const GlobalSearchRecord& g : result.global_searches) {
    *report.add_global_searches() = ToProto(g);
  }
  if (n > 0) {
    report.set_log_duration_s(dataset.scans[n - 1].timestamp - dataset.scans[0].timestamp);
  }

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

void PrintSearches(std::ostream& s, const proto::SlamParams& params) {
  const proto::RssLocalSearch& l = params.rss().local();
  s << "  local search: PSO of " << l.particles() << " particles x " << l.iterations()
    << " iterations on " << l.fitness() << ", map cells " << params.rss().map().cell_size_m()
    << " m, " << (l.odometry_tie_pull() > 0 ? "ties to odometry, " : "")
    << (l.second_swarm_above_rad() > 0 ? "a second swarm at odometry's heading, " : "")
    << (l.odometry_below_information() > 0 ? "odometry where the scan fixes nothing, " : "")
    << (l.odometry_weight() > 0 ? "odometry weighted " + FormatShortest(l.odometry_weight()) + ", "
                                : "")
    << (l.free_frontier() ? "the seen space's edge free, " : "")
    << (l.refine().iterations() > 0 ? "refined below a cell" : "not refined") << "\n";
  s << "  global search: ";
  const proto::RssGlobalSearch& g = params.rss().global();
  if (!g.enabled()) {
    s << "off\n";
    return;
  }
  s << (g.every_scans() > 0 ? "on a loop or every " + std::to_string(g.every_scans()) + " steps"
                            : std::string("on a loop"))
    << ", " << g.partitions() << " partitions, "
    << (g.beam_stride() > 1 ? "1 return in " + std::to_string(g.beam_stride()) + " scored"
                            : std::string("all returns scored"))
    << ", " << g.islands() << " islands of " << g.preset() << " x " << g.generations()
    << " generations\n";
}

void PrintLoops(std::ostream& s, const proto::SlamReport& r) {
  s << "  loops found: " << r.loops_size();
  const char* separator = " (scan ";
  for (const auto& loop : r.loops()) {
    s << separator << loop.later() << " back to " << loop.earlier() << ", score " << loop.score()
      << ", distinctness " << loop.distinctness();
    separator = "; scan ";
  }
  s << (r.loops().empty() ? "\n" : ")\n");
  int applied = 0;
  for (const auto& g : r.global_searches()) applied += g.applied();
  s << "  global searches: " << r.global_searches_size() << ", " << applied << " applied\n";
}

}  // namespace

std::string FormatSlamSummary(const proto::SlamReport& r) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  const auto& p = r.params();
  s << "SLAM (" << p.method() << ") over " << r.scans() << " scans of " << p.log() << ", "
    << r.log_duration_s() << " s of log\n";
  PrintSearches(s, p);
  const auto& t = r.times();
  s << "  time " << t.total_s() << " s: local search " << t.local_s() << " s, loop detection "
    << t.detection_s() << " s, global search " << t.global_s() << " s (" << r.scans_per_second()
    << " scans/s, " << r.threads() << " threads)\n";
  s << "  fitness evaluations: " << r.local_evaluations() << " local, " << r.global_evaluations()
    << " global\n";
  s << FormatOdometryStalls(r.odometry_stalls());
  PrintLoops(s, r);
  if (r.map_resolution_m() > p.rss().map().cell_size_m()) {
    s << "  map written at " << r.map_resolution_m() << " m per cell, not "
      << p.rss().map().cell_size_m()
      << ": the run's extent does not fit a map that fine\n";
  }
  if (r.has_absolute_errors()) {
    s << "  RMS error vs ground truth: " << FormatAbsoluteErrors(r.absolute_errors())
      << "\n    odometry alone: " << FormatAbsoluteErrors(r.odometry_absolute_errors()) << "\n";
  }
  if (r.has_relation_errors()) {
    const auto& e = r.relation_errors();
    s << "  relative error (" << e.source() << ", " << e.relations()
      << " relations): " << FormatRelationErrors(e)
      << "\n    odometry alone: " << FormatRelationErrors(r.odometry_relation_errors()) << "\n";
  }
  return s.str();
}

}  // namespace evoslam
