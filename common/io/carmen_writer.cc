#include "common/io/carmen_writer.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "common/io/carmen_format.h"
#include "common/io/text_fields.h"
#include "common/io/text_file_writer.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// Angles closer than this are the same FLASER geometry; over 361 beams it adds up to 0.002 deg.
constexpr double kAngleTolerance = 1e-7;
constexpr double kRangeMaxRelativeTolerance = 1e-9;
constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

constexpr std::string_view kHeader =
    "# CARMEN log written by evoslam\n"
    "# message_name [message contents] ipc_timestamp ipc_hostname logger_timestamp\n"
    "# PARAM param_name param_value\n"
    "# ODOM x y theta tv rv accel\n"
    "# FLASER num_readings [range_readings] x y theta odom_x odom_y odom_theta\n"
    "# RLASER num_readings [range_readings] x y theta odom_x odom_y odom_theta\n"
    "# ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy "
    "remission_mode num_readings [range_readings] num_remissions [remissions] laser_pose_x "
    "laser_pose_y laser_pose_theta robot_pose_x robot_pose_y robot_pose_theta laser_tv laser_rv "
    "forward_safety_dist side_safety_dist turn_axis\n"
    "# ROBOTLASER2 as ROBOTLASER1, for the rear laser\n"
    "# TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta\n";

bool HasSpace(std::string_view text) {
  return text.find_first_of(" \t\r\n\v\f") != std::string_view::npos;
}

// Appends fields separated by single spaces.
class LineBuilder {
 public:
  explicit LineBuilder(std::string* out) : out_(*out) {}

  void Text(std::string_view text) {
    Separate();
    out_ += text;
  }
  void Count(std::size_t value) { Append(value); }
  void Shortest(double value) { Append(value); }
  void Shortest(float value) { Append(value); }
  void Timestamp(double value) { Append(value, std::chars_format::fixed, 6); }
  void PoseFields(const Pose2& pose) {
    Shortest(pose.x());
    Shortest(pose.y());
    Shortest(pose.theta());
  }
  void End() {
    out_ += '\n';
    first_ = true;
  }

 private:
  void Separate() {
    if (!first_) out_ += ' ';
    first_ = false;
  }
  template <typename T, typename... Format>
  void Append(T value, Format... format) {
    Separate();
    // Room for any finite double in fixed notation.
    char buffer[400];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value, format...);
    out_.append(buffer, result.ptr);
  }

  std::string& out_;
  bool first_ = true;
};

class CarmenWriter {
 public:
  CarmenWriter(const Dataset& dataset, const std::filesystem::path& path)
      : dataset_(dataset),
        path_(path.string()),
        front_range_max_(CarmenRangeMax(dataset.params, false)),
        rear_range_max_(CarmenRangeMax(dataset.params, true)),
        file_(path) {}

  void Write() {
    out_ += kHeader;
    for (const auto& [name, value] : dataset_.params) WriteParam(name, value);
    // Merge the three streams by timestamp, each in its own order, so that reading the file back
    // gives every vector in the same order even if its timestamps are not sorted.
    const std::vector<OdometryReading>& odometry = dataset_.odometry;
    const std::vector<LaserScan>& front = dataset_.scans;
    const std::vector<LaserScan>& rear = dataset_.rear_scans;
    std::size_t o = 0;
    std::size_t f = 0;
    std::size_t r = 0;
    while (o < odometry.size() || f < front.size() || r < rear.size()) {
      // Ties go to odometry, then front, then rear.
      int pick = -1;
      double earliest = 0.0;
      const auto consider = [&](const auto& items, std::size_t next, int stream) {
        if (next < items.size() && (pick < 0 || items[next].timestamp < earliest)) {
          pick = stream;
          earliest = items[next].timestamp;
        }
      };
      consider(odometry, o, 0);
      consider(front, f, 1);
      consider(rear, r, 2);
      if (pick == 0) {
        WriteOdometry(odometry[o], o);
        ++o;
      } else if (pick == 1) {
        WriteScan(front[f], f, false);
        ++f;
      } else {
        WriteScan(rear[r], r, true);
        ++r;
      }
      if (out_.size() >= kFlushBytes) Flush();
    }
    Flush();
    file_.Close();
  }

 private:
  [[noreturn]] void Fail(std::string_view what) const {
    throw Error(fmt::format("cannot write {}: {}", path_, what));
  }

  void Flush() {
    file_.Write(out_);
    out_.clear();
  }

  void RequireFinite(double value, std::string_view what, std::size_t index,
                     std::string_view field) const {
    if (!std::isfinite(value)) Fail(fmt::format("{} {} has {} = {}", what, index, field, value));
  }
  void RequireFinite(const Pose2& pose, std::string_view what, std::size_t index,
                     std::string_view field) const {
    RequireFinite(pose.x(), what, index, field);
    RequireFinite(pose.y(), what, index, field);
    RequireFinite(pose.theta(), what, index, field);
  }
  void RequireHostname(std::string_view hostname, std::string_view what, std::size_t index) const {
    if (hostname.empty() || HasSpace(hostname)) {
      Fail(fmt::format("{} {} has hostname '{}'; CARMEN needs one word", what, index, hostname));
    }
  }

  void WriteParam(const std::string& name, const std::string& value) {
    if (name.empty() || HasSpace(name)) {
      Fail(fmt::format("PARAM name '{}' must be one word", name));
    }
    std::vector<std::string_view> words;
    SplitFields(value, &words);
    std::string joined;
    for (const std::string_view word : words) {
      if (!joined.empty()) joined += ' ';
      joined += word;
    }
    if (value.empty() || joined != value || value.find('\n') != std::string::npos) {
      Fail(
          fmt::format("PARAM {} value '{}' must be words separated by single spaces", name, value));
    }
    if ((IsRangeMaxParam(name, false) || IsRangeMaxParam(name, true)) &&
        !ParseRangeMaxParam(value)) {
      Fail(fmt::format("PARAM {} is '{}', expected a positive number", name, value));
    }
    // CARMEN's full form, with an ipc_timestamp, so that a value ending in a number reads back.
    LineBuilder line(&out_);
    line.Text("PARAM");
    line.Text(name);
    line.Text(value);
    line.Timestamp(0.0);
    line.Text("nohost");
    line.Timestamp(0.0);
    line.End();
  }

  void WriteOdometry(const OdometryReading& odom, std::size_t index) {
    constexpr std::string_view kWhat = "odometry reading";
    RequireFinite(odom.pose, kWhat, index, "pose");
    RequireFinite(odom.tv, kWhat, index, "tv");
    RequireFinite(odom.rv, kWhat, index, "rv");
    RequireFinite(odom.accel, kWhat, index, "accel");
    RequireFinite(odom.timestamp, kWhat, index, "timestamp");
    RequireFinite(odom.logger_timestamp, kWhat, index, "logger_timestamp");
    RequireHostname(odom.hostname, kWhat, index);
    LineBuilder line(&out_);
    line.Text("ODOM");
    line.PoseFields(odom.pose);
    line.Shortest(odom.tv);
    line.Shortest(odom.rv);
    line.Shortest(odom.accel);
    Stamps(line, odom.timestamp, odom.hostname, odom.logger_timestamp);
    line.End();
  }

  static void Stamps(LineBuilder& line, double timestamp, std::string_view hostname,
                     double logger_timestamp) {
    line.Timestamp(timestamp);
    line.Text(hostname);
    line.Timestamp(logger_timestamp);
  }

  bool FitsFlaser(const LaserScan& scan, bool rear) const {
    if (scan.message == LaserMessage::kRobotLaser) return false;
    const double range_max = rear ? rear_range_max_ : front_range_max_;
    return std::abs(scan.angle_min - kFlaserAngleMin) <= kAngleTolerance &&
           std::abs(scan.angle_increment - FlaserAngleIncrement(scan.size())) <= kAngleTolerance &&
           std::abs(scan.range_max - range_max) <= kRangeMaxRelativeTolerance * range_max;
  }

  void WriteScan(const LaserScan& scan, std::size_t index, bool rear) {
    const std::string_view what = rear ? "rear scan" : "scan";
    for (std::size_t i = 0; i < scan.size(); ++i) {
      if (!IsFiniteNonNegative(scan.ranges[i])) {
        Fail(fmt::format("{} {} has range {} at beam {}; CARMEN ranges are finite and >= 0", what,
                         index, scan.ranges[i], i));
      }
    }
    RequireFinite(scan.pose, what, index, "pose");
    RequireFinite(scan.odometry, what, index, "odometry");
    RequireFinite(scan.timestamp, what, index, "timestamp");
    RequireFinite(scan.logger_timestamp, what, index, "logger_timestamp");
    RequireHostname(scan.hostname, what, index);
    if (scan.true_pose) RequireFinite(*scan.true_pose, what, index, "true pose");

    LineBuilder line(&out_);
    if (FitsFlaser(scan, rear)) {
      line.Text(rear ? "RLASER" : "FLASER");
      line.Count(scan.size());
      for (const float range : scan.ranges) line.Shortest(range);
      line.PoseFields(scan.pose);
      line.PoseFields(scan.odometry);
    } else {
      RequireFinite(scan.angle_min, what, index, "angle_min");
      RequireFinite(scan.angle_increment, what, index, "angle_increment");
      if (!IsFinitePositive(scan.range_max)) {
        Fail(fmt::format("{} {} has range_max {}, expected a positive number", what, index,
                         scan.range_max));
      }
      // Dataset keeps no laser type, accuracy, remission mode, velocities, safety distances or
      // turn axis: they are written as 0. The laser pose is written as the robot pose.
      line.Text(rear ? "ROBOTLASER2" : "ROBOTLASER1");
      line.Count(0);
      line.Shortest(scan.angle_min);
      line.Shortest(scan.field_of_view());
      line.Shortest(scan.angle_increment);
      line.Shortest(scan.range_max);
      line.Count(0);
      line.Count(0);
      line.Count(scan.size());
      for (const float range : scan.ranges) line.Shortest(range);
      line.Count(0);
      line.PoseFields(scan.pose);
      line.PoseFields(scan.pose);
      for (int i = 0; i < 5; ++i) line.Count(0);
    }
    Stamps(line, scan.timestamp, scan.hostname, scan.logger_timestamp);
    line.End();

    if (scan.true_pose) {
      line.Text("TRUEPOS");
      line.PoseFields(*scan.true_pose);
      line.PoseFields(scan.odometry);
      Stamps(line, scan.timestamp, scan.hostname, scan.logger_timestamp);
      line.End();
    }
  }

  const Dataset& dataset_;
  std::string path_;
  double front_range_max_;
  double rear_range_max_;
  TextFileWriter file_;
  std::string out_;
};

}  // namespace

void WriteCarmen(const Dataset& dataset, const std::filesystem::path& path) {
  CarmenWriter(dataset, path).Write();
}

}  // namespace evoslam
