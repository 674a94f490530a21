#include "common/io/trajectory_io.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

#include "common/io/line_reader.h"
#include "common/io/text_fields.h"
#include "common/io/text_file_writer.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kTextFields = 4;
constexpr std::size_t kTumFields = 8;
constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

// Writes one line per pose, formatted by `line`, after `header`.
template <typename FormatLine>
void WriteLines(std::span<const StampedPose> poses, const std::filesystem::path& path,
                std::string_view header, FormatLine line) {
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const StampedPose& p = poses[i];
    if (!std::isfinite(p.timestamp) || !std::isfinite(p.pose.x()) || !std::isfinite(p.pose.y()) ||
        !std::isfinite(p.pose.theta())) {
      throw Error(fmt::format("cannot write {}: pose {} is not finite (t {} x {} y {} theta {})",
                              path.string(), i, p.timestamp, p.pose.x(), p.pose.y(),
                              p.pose.theta()));
    }
  }
  TextFileWriter file(path);
  std::string out(header);
  for (const StampedPose& p : poses) {
    line(p, &out);
    if (out.size() >= kFlushBytes) {
      file.Write(out);
      out.clear();
    }
  }
  file.Write(out);
  file.Close();
}

[[noreturn]] void Fail(const LineReader& reader, const std::string& message) {
  throw InputError(reader.source(), reader.line_number(), message);
}

}  // namespace

void WriteTrajectoryText(std::span<const StampedPose> poses, const std::filesystem::path& path) {
  WriteLines(poses, path, "# timestamp x y theta\n", [](const StampedPose& p, std::string* out) {
    fmt::format_to(std::back_inserter(*out), "{:.6f} {:.9g} {:.9g} {:.9g}\n", p.timestamp,
                   p.pose.x(), p.pose.y(), p.pose.theta());
  });
}

void WriteTrajectoryTum(std::span<const StampedPose> poses, const std::filesystem::path& path) {
  WriteLines(poses, path, "# timestamp tx ty tz qx qy qz qw\n",
             [](const StampedPose& p, std::string* out) {
               const double half = 0.5 * p.pose.theta();
               fmt::format_to(std::back_inserter(*out),
                              "{:.6f} {:.9g} {:.9g} 0 0 0 {:.9g} {:.9g}\n", p.timestamp, p.pose.x(),
                              p.pose.y(), std::sin(half), std::cos(half));
             });
}

std::vector<StampedPose> ReadTrajectory(const std::filesystem::path& path) {
  LineReader reader(path);
  std::vector<StampedPose> poses;
  std::vector<std::string_view> fields;
  std::size_t format_fields = 0;  // set by the first data line
  std::size_t format_line = 0;
  while (const std::optional<std::string_view> line = reader.Next()) {
    SplitFields(*line, &fields);
    if (fields.empty() || fields[0].front() == '#') continue;
    if (format_fields == 0) {
      if (fields.size() != kTextFields && fields.size() != kTumFields) {
        Fail(reader,
             fmt::format(
                 "expected 4 fields (t x y theta) or 8 fields (TUM: t x y z qx qy qz qw), found {}",
                 fields.size()));
      }
      format_fields = fields.size();
      format_line = reader.line_number();
    } else if (fields.size() != format_fields) {
      Fail(reader, fmt::format("expected {} fields like line {}, found {}", format_fields,
                               format_line, fields.size()));
    }
    double values[kTumFields];
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::optional<double> value = ParseDouble(fields[i]);
      if (!value || !std::isfinite(*value)) {
        Fail(reader, fmt::format("field {} is '{}', expected a finite number", i + 1, fields[i]));
      }
      values[i] = *value;
    }
    StampedPose pose;
    pose.timestamp = values[0];
    if (format_fields == kTextFields) {
      pose.pose = Pose2(values[1], values[2], values[3]);
    } else {
      const double qx = values[4];
      const double qy = values[5];
      const double qz = values[6];
      const double qw = values[7];
      const double norm2 = qx * qx + qy * qy + qz * qz + qw * qw;
      if (!(norm2 > 1e-12)) Fail(reader, "quaternion qx qy qz qw has zero length");
      // Heading of the rotation, scaled so that a quaternion need not be normalised.
      const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), norm2 - 2.0 * (qy * qy + qz * qz));
      pose.pose = Pose2(values[1], values[2], yaw);
    }
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace evoslam
