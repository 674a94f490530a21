#include "common/sensor/dataset_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <locale>
#include <span>
#include <sstream>
#include <vector>

#include "common/sensor/odometry_stalls.h"
#include "common/transform/angle_units.h"

namespace evoslam {
namespace {

template <typename Item, typename PoseOf>
double PathLength(std::span<const Item> items, PoseOf pose_of) {
  double length = 0.0;
  for (std::size_t i = 1; i < items.size(); ++i) {
    length += (pose_of(items[i]).translation() - pose_of(items[i - 1]).translation()).norm();
  }
  return length;
}

template <typename Item>
void ExtendTimes(std::span<const Item> items, bool* any, double* start, double* end) {
  for (const Item& item : items) {
    if (!*any) {
      *start = *end = item.timestamp;
      *any = true;
    }
    *start = std::min(*start, item.timestamp);
    *end = std::max(*end, item.timestamp);
  }
}

}  // namespace

DatasetSummary Summarize(const Dataset& dataset) {
  DatasetSummary s;
  s.scans = dataset.scans.size();
  s.rear_scans = dataset.rear_scans.size();
  s.odometry_readings = dataset.odometry.size();
  if (!dataset.scans.empty()) {
    s.min_beams = s.max_beams = dataset.scans.front().size();
    s.angle_increment_deg = Degrees(dataset.scans.front().angle_increment);
    for (const LaserScan& scan : dataset.scans) {
      s.min_beams = std::min(s.min_beams, scan.size());
      s.max_beams = std::max(s.max_beams, scan.size());
      s.field_of_view_deg = std::max(s.field_of_view_deg, Degrees(scan.field_of_view()));
      s.max_range = std::max(s.max_range, scan.range_max);
    }
  }
  bool any = false;
  ExtendTimes(std::span<const LaserScan>(dataset.scans), &any, &s.start_time, &s.end_time);
  ExtendTimes(std::span<const LaserScan>(dataset.rear_scans), &any, &s.start_time, &s.end_time);
  ExtendTimes(std::span<const OdometryReading>(dataset.odometry), &any, &s.start_time, &s.end_time);
  s.duration = s.end_time - s.start_time;
  // ODOM messages come at the odometry's own rate, often faster than the laser's, so they follow
  // the path more closely than the odometry stamped on the scans; the scans' are the fallback
  // for logs without ODOM lines (MIT CSAIL, simulated logs).
  if (dataset.odometry.size() >= 2) {
    s.odometry_path_length = PathLength(std::span<const OdometryReading>(dataset.odometry),
                                        [](const OdometryReading& o) { return o.pose; });
  } else {
    s.odometry_path_length = PathLength(std::span<const LaserScan>(dataset.scans),
                                        [](const LaserScan& scan) { return scan.odometry; });
  }
  const std::vector<OdometryStall> repeats = FindRepeatedReadings(dataset.scans);
  s.odometry_repeats = repeats.size();
  for (const OdometryStall& run : repeats) {
    s.longest_odometry_repeat = std::max(s.longest_odometry_repeat, run.last + 1 - run.first);
    s.largest_catch_up_m = std::max(s.largest_catch_up_m, run.catch_up.translation().norm());
    s.largest_catch_up_deg =
        std::max(s.largest_catch_up_deg, Degrees(std::abs(run.catch_up.theta())));
  }
  s.has_ground_truth = dataset.has_ground_truth();
  s.anomalies = FindLogAnomalies(dataset.scans);
  return s;
}

std::string FormatSummary(const DatasetSummary& s) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << std::fixed << std::setprecision(2);
  out << "scans:             " << s.scans << " (front), " << s.rear_scans << " (rear)\n";
  out << "odometry readings: " << s.odometry_readings << "\n";
  out << "beams per scan:    " << s.min_beams;
  if (s.max_beams != s.min_beams) out << " to " << s.max_beams;
  out << "\n";
  out << "field of view:     " << s.field_of_view_deg << " deg, " << std::setprecision(3)
      << s.angle_increment_deg << " deg between beams\n";
  out << std::setprecision(2) << "max range:         " << s.max_range << " m\n";
  out << std::setprecision(3) << "time:              " << s.start_time << " to " << s.end_time
      << " s (" << std::setprecision(1) << s.duration << " s)\n";
  out << std::setprecision(2) << "odometry path:     " << s.odometry_path_length << " m\n";
  out << "odometry repeats:  ";
  if (s.odometry_repeats == 0) {
    out << "none\n";
  } else {
    out << s.odometry_repeats << " runs of scans, the longest " << s.longest_odometry_repeat
        << "; the steps that end them up to " << s.largest_catch_up_m << " m and "
        << std::setprecision(1) << s.largest_catch_up_deg << " deg\n";
  }
  out << "odometry jumps:    ";
  if (s.anomalies.jumps.empty()) {
    out << "none\n";
  } else {
    out << s.anomalies.jumps.size() << " steps far beyond the " << s.anomalies.typical_step_m
        << " m pace:";
    for (const OdometryJump& jump : s.anomalies.jumps) {
      out << " " << jump.length_m << " m from scan " << jump.from << " to " << jump.from + 1 << ";";
    }
    out << "\n";
  }
  out << "time going back:   ";
  if (s.anomalies.reversals.empty()) {
    out << "never\n";
  } else {
    out << s.anomalies.reversals.size() << " times, the scans are taken in file order:";
    for (const TimeReversal& reversal : s.anomalies.reversals) {
      out << " at scan " << reversal.scan << " by " << reversal.back_s << " s;";
    }
    out << "\n";
  }
  out << "ground truth:      " << (s.has_ground_truth ? "yes" : "no") << "\n";
  return out.str();
}

}  // namespace evoslam
