#include "common/io/carmen_reader.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/io/carmen_format.h"
#include "common/io/line_reader.h"
#include "common/io/text_fields.h"
#include "common/util/counted.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

constexpr std::size_t kFlaserTrailing = 9;
constexpr std::string_view kFlaserTrailingNames =
    "x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname logger_timestamp";
constexpr std::size_t kRobotLaserHead = 9;  // message name up to num_readings
constexpr std::size_t kRobotLaserTrailing = 14;
constexpr std::string_view kRobotLaserTrailingNames =
    "laser_pose_x laser_pose_y laser_pose_theta robot_pose_x robot_pose_y robot_pose_theta "
    "laser_tv laser_rv forward_safety_dist side_safety_dist turn_axis ipc_timestamp "
    "ipc_hostname logger_timestamp";
constexpr std::size_t kOdomFields = 9;
constexpr std::size_t kTrueposFields = 9;

// Reads the fields of one message; every failure is an InputError naming the message and what
// was expected.
class FieldParser {
 public:
  FieldParser(std::span<const std::string_view> fields, const std::string& source, std::size_t line)
      : fields_(fields), source_(source), line_(line) {}

  std::size_t size() const { return fields_.size(); }
  std::string_view text(std::size_t i) const { return fields_[i]; }

  [[noreturn]] void Fail(std::string_view message) const {
    throw InputError(source_, line_, fmt::format("{}: {}", fields_[0], message));
  }

  double Number(std::size_t i, std::string_view name) const {
    const std::optional<double> value = ParseDouble(fields_[i]);
    if (!value) Fail(fmt::format("{} is '{}', expected a number", name, fields_[i]));
    if (!std::isfinite(*value)) {
      Fail(fmt::format("{} is '{}', expected a finite number", name, fields_[i]));
    }
    return *value;
  }

  std::size_t Count(std::size_t i, std::string_view name) const {
    const std::optional<std::size_t> value = ParseCount(fields_[i]);
    if (!value) Fail(fmt::format("{} is '{}', expected a count >= 0", name, fields_[i]));
    return *value;
  }

  // Beam `beam` (0-based) of `beams`; messages count beams from 1 as people do.
  float Range(std::size_t i, std::size_t beam, std::size_t beams) const {
    const std::optional<float> value = ParseFloat(fields_[i]);
    if (!value || !IsFiniteNonNegative(*value)) {
      Fail(fmt::format("range {} of {} is '{}', expected a finite number >= 0", beam + 1, beams,
                       fields_[i]));
    }
    return *value;
  }

  Pose2 PoseAt(std::size_t i, std::string_view x, std::string_view y,
               std::string_view theta) const {
    return {Number(i, x), Number(i + 1, y), Number(i + 2, theta)};
  }

 private:
  std::span<const std::string_view> fields_;
  const std::string& source_;
  std::size_t line_;
};

// FLASER/RLASER: num_readings [ranges] x y theta odom_x odom_y odom_theta ipc_timestamp
// ipc_hostname logger_timestamp.
LaserScan ParseFlaser(const FieldParser& p, LaserMessage message) {
  if (p.size() < 2) p.Fail("expected the number of ranges, found nothing");
  const std::size_t n = p.Count(1, "num_readings");
  const std::size_t after = p.size() - 2;
  if (after < n || after - n != kFlaserTrailing) {
    p.Fail(fmt::format("expected {} ranges + {} fields ({}), found {} fields after num_readings", n,
                       kFlaserTrailing, kFlaserTrailingNames, after));
  }
  LaserScan scan;
  scan.message = message;
  scan.angle_min = kFlaserAngleMin;
  scan.angle_increment = FlaserAngleIncrement(n);
  scan.ranges.resize(n);
  for (std::size_t i = 0; i < n; ++i) scan.ranges[i] = p.Range(2 + i, i, n);
  const std::size_t k = 2 + n;
  scan.pose = p.PoseAt(k, "x", "y", "theta");
  scan.odometry = p.PoseAt(k + 3, "odom_x", "odom_y", "odom_theta");
  scan.timestamp = p.Number(k + 6, "ipc_timestamp");
  scan.hostname = p.text(k + 7);
  scan.logger_timestamp = p.Number(k + 8, "logger_timestamp");
  return scan;
}

// ROBOTLASER1/2: laser_type start_angle field_of_view angular_resolution maximum_range accuracy
// remission_mode num_readings [ranges] num_remissions [remissions] laser_pose robot_pose laser_tv
// laser_rv forward_safety_dist side_safety_dist turn_axis ipc_timestamp ipc_hostname
// logger_timestamp. The laser pose is not kept: robot_pose is both the scan's pose and its
// odometry, and the scan's geometry is the message's own.
LaserScan ParseRobotLaser(const FieldParser& p, LaserMessage message) {
  if (p.size() < kRobotLaserHead) {
    p.Fail(fmt::format(
        "expected laser_type start_angle field_of_view angular_resolution maximum_range accuracy "
        "remission_mode num_readings, found {} fields",
        p.size() - 1));
  }
  p.Number(1, "laser_type");
  LaserScan scan;
  scan.message = message;
  scan.angle_min = p.Number(2, "start_angle");
  p.Number(3, "field_of_view");
  scan.angle_increment = p.Number(4, "angular_resolution");
  scan.range_max = p.Number(5, "maximum_range");
  if (scan.range_max <= 0.0) {
    p.Fail(fmt::format("maximum_range is '{}', expected a positive number", p.text(5)));
  }
  p.Number(6, "accuracy");
  p.Number(7, "remission_mode");
  const std::size_t n = p.Count(8, "num_readings");
  const std::size_t after = p.size() - kRobotLaserHead;
  if (after < n || after - n < 1) {
    p.Fail(fmt::format("expected {} ranges + num_remissions, found {} fields after num_readings", n,
                       after));
  }
  scan.ranges.resize(n);
  for (std::size_t i = 0; i < n; ++i) scan.ranges[i] = p.Range(kRobotLaserHead + i, i, n);
  const std::size_t remission_index = kRobotLaserHead + n;
  const std::size_t m = p.Count(remission_index, "num_remissions");
  const std::size_t rest = after - n - 1;
  if (rest < m || rest - m != kRobotLaserTrailing) {
    p.Fail(
        fmt::format("expected {} remissions + {} fields ({}), found {} fields after num_remissions",
                    m, kRobotLaserTrailing, kRobotLaserTrailingNames, rest));
  }
  for (std::size_t i = 0; i < m; ++i) p.Number(remission_index + 1 + i, "remission");
  const std::size_t k = remission_index + 1 + m;
  p.PoseAt(k, "laser_pose_x", "laser_pose_y", "laser_pose_theta");
  scan.pose = p.PoseAt(k + 3, "robot_pose_x", "robot_pose_y", "robot_pose_theta");
  scan.odometry = scan.pose;
  p.Number(k + 6, "laser_tv");
  p.Number(k + 7, "laser_rv");
  p.Number(k + 8, "forward_safety_dist");
  p.Number(k + 9, "side_safety_dist");
  p.Number(k + 10, "turn_axis");
  scan.timestamp = p.Number(k + 11, "ipc_timestamp");
  scan.hostname = p.text(k + 12);
  scan.logger_timestamp = p.Number(k + 13, "logger_timestamp");
  return scan;
}

OdometryReading ParseOdom(const FieldParser& p) {
  if (p.size() - 1 != kOdomFields) {
    p.Fail(fmt::format(
        "expected {} fields (x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp), "
        "found {}",
        kOdomFields, p.size() - 1));
  }
  OdometryReading odom;
  odom.pose = p.PoseAt(1, "x", "y", "theta");
  odom.tv = p.Number(4, "tv");
  odom.rv = p.Number(5, "rv");
  odom.accel = p.Number(6, "accel");
  odom.timestamp = p.Number(7, "ipc_timestamp");
  odom.hostname = p.text(8);
  odom.logger_timestamp = p.Number(9, "logger_timestamp");
  return odom;
}

struct TruePose {
  double timestamp = 0.0;
  Pose2 pose;
};

TruePose ParseTruepos(const FieldParser& p) {
  if (p.size() - 1 != kTrueposFields) {
    p.Fail(fmt::format(
        "expected {} fields (true_x true_y true_theta odom_x odom_y odom_theta ipc_timestamp "
        "ipc_hostname logger_timestamp), found {}",
        kTrueposFields, p.size() - 1));
  }
  TruePose truth;
  truth.pose = p.PoseAt(1, "true_x", "true_y", "true_theta");
  p.PoseAt(4, "odom_x", "odom_y", "odom_theta");
  truth.timestamp = p.Number(7, "ipc_timestamp");
  p.Number(9, "logger_timestamp");
  return truth;
}

bool IsNumber(std::string_view text) { return ParseDouble(text).has_value(); }

// PARAM name value, optionally followed by [ipc_timestamp] ipc_hostname logger_timestamp (CARMEN
// writes all three; converted logs such as Intel's only the last two). A value may hold spaces,
// so the trailing fields are recognised by their form: a non-number then a number at the end,
// and before them a number when the value would keep at least one field.
std::pair<std::string, std::string> ParseParam(const FieldParser& p) {
  if (p.size() < 3) p.Fail("expected a name and a value");
  std::size_t last = p.size();  // one past the value's last field
  if (last - 2 >= 3 && IsNumber(p.text(last - 1)) && !IsNumber(p.text(last - 2))) {
    last -= 2;
    if (last - 2 >= 2 && IsNumber(p.text(last - 1))) --last;
  }
  std::string value(p.text(2));
  for (std::size_t i = 3; i < last; ++i) {
    value += ' ';
    value += p.text(i);
  }
  const std::string_view name = p.text(1);
  if ((IsRangeMaxParam(name, false) || IsRangeMaxParam(name, true)) && !ParseRangeMaxParam(value)) {
    p.Fail(fmt::format("{} is '{}', expected a positive number", name, value));
  }
  return {std::string(name), std::move(value)};
}

}  // namespace

Dataset ReadCarmen(const std::filesystem::path& path, const CarmenReadOptions& options,
                   CarmenReadStats* stats) {
  LineReader reader(path);
  Dataset dataset;
  dataset.source = reader.source();
  CarmenReadStats counts;
  std::vector<std::string_view> fields;
  std::vector<TruePose> truths;
  // FLASER/RLASER scans get their range_max from PARAMs that may come anywhere in the log.
  std::vector<std::size_t> flaser_scans;
  std::vector<std::size_t> rlaser_scans;

  while (const std::optional<std::string_view> line = reader.Next()) {
    SplitFields(*line, &fields);
    if (fields.empty() || fields[0].front() == '#') continue;
    const FieldParser parser(fields, reader.source(), reader.line_number());
    const std::string_view name = fields[0];
    try {
      if (name == "ODOM") {
        dataset.odometry.push_back(ParseOdom(parser));
      } else if (name == "FLASER") {
        dataset.scans.push_back(ParseFlaser(parser, LaserMessage::kFront));
        flaser_scans.push_back(dataset.scans.size() - 1);
      } else if (name == "RLASER") {
        dataset.rear_scans.push_back(ParseFlaser(parser, LaserMessage::kRear));
        rlaser_scans.push_back(dataset.rear_scans.size() - 1);
      } else if (name == "ROBOTLASER1") {
        dataset.scans.push_back(ParseRobotLaser(parser, LaserMessage::kRobotLaser));
      } else if (name == "ROBOTLASER2") {
        dataset.rear_scans.push_back(ParseRobotLaser(parser, LaserMessage::kRear));
      } else if (name == "TRUEPOS") {
        truths.push_back(ParseTruepos(parser));
      } else if (name == "PARAM") {
        dataset.params.push_back(ParseParam(parser));
      }
    } catch (const InputError& e) {
      if (!options.lenient) throw;
      if (counts.skipped++ == 0) {
        counts.first_skip_line = e.line();
        counts.first_skip_reason = e.message();
      }
    }
  }
  counts.lines = reader.line_number();
  if (dataset.scans.empty()) {
    // Nothing can be mapped or described from it: most likely not a CARMEN log at all.
    std::string what = "no laser scans (FLASER or ROBOTLASER1 lines) in its " +
                       std::to_string(counts.lines) + " lines";
    if (!dataset.odometry.empty()) {
      what += ", only " + Counted(dataset.odometry.size(), "odometry reading");
    }
    if (counts.skipped > 0) {
      what += "; skipped " + Counted(counts.skipped, "malformed line") + ", the first at line " +
              std::to_string(counts.first_skip_line) + ": " + counts.first_skip_reason;
    }
    throw InputError(reader.source(), 0, what);
  }

  const double front_max = CarmenRangeMax(dataset.params, false);
  const double rear_max = CarmenRangeMax(dataset.params, true);
  for (const std::size_t i : flaser_scans) dataset.scans[i].range_max = front_max;
  for (const std::size_t i : rlaser_scans) dataset.rear_scans[i].range_max = rear_max;

  // A TRUEPOS may come before or after its scan; the last one for a timestamp wins.
  std::unordered_map<double, Pose2> truth_at;
  for (const TruePose& truth : truths) truth_at[truth.timestamp] = truth.pose;
  if (!truth_at.empty()) {
    for (std::vector<LaserScan>* scans : {&dataset.scans, &dataset.rear_scans}) {
      for (LaserScan& scan : *scans) {
        if (const auto it = truth_at.find(scan.timestamp); it != truth_at.end()) {
          scan.true_pose = it->second;
        }
      }
    }
  }
  dataset.skipped_lines = counts.skipped;
  if (stats != nullptr) *stats = std::move(counts);
  return dataset;
}

}  // namespace evoslam
