#include "common/slam/immune/trajectory_segments.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

void RequirePositive(double value, const char* field) {
  if (!IsFinitePositive(value)) {
    throw Error(fmt::format("immune.segments.{} must be positive, not {}", field, value));
  }
}

}  // namespace

void ValidateTrajectorySegmentParams(const proto::TrajectorySegmentParams& params) {
  RequirePositive(params.length_m(), "length_m");
  RequirePositive(params.max_turn_rad(), "max_turn_rad");
  RequirePositive(params.key_point_length_m(), "key_point_length_m");
  RequirePositive(params.max_length_correction_m(), "max_length_correction_m");
  RequirePositive(params.max_turn_correction_deg(), "max_turn_correction_deg");
  if (params.max_turn_correction_deg() >= 180.0) {
    throw Error(fmt::format("immune.segments.max_turn_correction_deg must be below 180, not {}",
                            params.max_turn_correction_deg()));
  }
  if (params.encoding() != "integer" && params.encoding() != "continuous") {
    throw Error("immune.segments.encoding must be integer or continuous, not '" +
                params.encoding() + "'");
  }
  RequirePositive(params.length_unit_m(), "length_unit_m");
  RequirePositive(params.turn_unit_deg(), "turn_unit_deg");
}

std::vector<TrajectorySegment> CutSegments(std::span<const Pose2> poses,
                                           std::span<const std::size_t> fine_scans,
                                           const proto::TrajectorySegmentParams& params) {
  std::vector<TrajectorySegment> segments;
  if (poses.size() < 2) return segments;
  auto next_fine = fine_scans.begin();
  TrajectorySegment current;
  bool fine = false;  // the current segment starts at a fine scan
  for (std::size_t k = 1; k < poses.size(); ++k) {
    // A fine scan ends the segment before it and starts a short one.
    const std::size_t from = k - 1;
    while (next_fine != fine_scans.end() && *next_fine < from) ++next_fine;
    if (next_fine != fine_scans.end() && *next_fine == from) {
      if (from > current.first) {
        segments.push_back(current);
        current = {.first = from, .last = from};
      }
      fine = true;
    }
    const Pose2 step = poses[k - 1].inverse() * poses[k];
    current.length += step.translation().norm();
    current.turn += step.theta();
    current.last = k;
    const double limit = fine ? params.key_point_length_m() : params.length_m();
    if (current.length >= limit || std::abs(current.turn) >= params.max_turn_rad()) {
      segments.push_back(current);
      current = {.first = k, .last = k};
      fine = false;
    }
  }
  if (current.last > current.first) segments.push_back(current);
  return segments;
}

SegmentedTrajectory::SegmentedTrajectory(std::span<const Pose2> poses,
                                         std::vector<TrajectorySegment> segments)
    : start_(poses.empty() ? Pose2() : poses.front()), segments_(std::move(segments)) {
  steps_.reserve(poses.size() > 0 ? poses.size() - 1 : 0);
  for (std::size_t k = 1; k < poses.size(); ++k)
    steps_.push_back(poses[k - 1].inverse() * poses[k]);
  turn_share_.assign(steps_.size(), 0.0);
  std::size_t expected_first = 0;
  for (const TrajectorySegment& s : segments_) {
    if (s.first != expected_first || s.last <= s.first || s.last > steps_.size()) {
      throw Error("segments must cover the trajectory's scans in order, each at least one step");
    }
    expected_first = s.last;
    double travelled = 0.0;
    for (std::size_t k = s.first; k < s.last; ++k) travelled += steps_[k].translation().norm();
    for (std::size_t k = s.first; k < s.last; ++k) {
      turn_share_[k] = travelled > 0.0 ? steps_[k].translation().norm() / travelled
                                       : 1.0 / static_cast<double>(s.last - s.first);
    }
  }
  if (!segments_.empty() && expected_first != steps_.size()) {
    throw Error("segments must cover the trajectory's scans in order, each at least one step");
  }
}

void SegmentedTrajectory::Poses(std::size_t first, std::span<const SegmentCorrection> corrections,
                                const Pose2& from, std::span<Pose2> out) const {
  if (corrections.empty()) return;
  const std::size_t first_scan = segments_.at(first).first;
  const std::size_t last_scan = segments_.at(first + corrections.size() - 1).last;
  if (out.size() != last_scan - first_scan + 1) {
    throw Error("SegmentedTrajectory::Poses: room for " + std::to_string(out.size()) +
                " poses, not the " + std::to_string(last_scan - first_scan + 1) + " asked for");
  }
  Pose2 pose = from;
  out[0] = pose;
  for (std::size_t j = 0; j < corrections.size(); ++j) {
    const TrajectorySegment& s = segments_[first + j];
    const double scale = s.length > 0.0 ? (s.length + corrections[j].length) / s.length : 1.0;
    for (std::size_t k = s.first; k < s.last; ++k) {
      const Pose2& step = steps_[k];
      pose = pose *
             Pose2(step.translation() * scale, step.theta() + corrections[j].turn * turn_share_[k]);
      out[k + 1 - first_scan] = pose;
    }
  }
}

std::vector<Pose2> SegmentedTrajectory::AllPoses(
    std::span<const SegmentCorrection> corrections) const {
  if (corrections.size() != segments_.size()) {
    throw Error("a correction for each of the " + std::to_string(segments_.size()) +
                " segments, not " + std::to_string(corrections.size()));
  }
  std::vector<Pose2> poses(scans(), start_);
  if (!segments_.empty()) Poses(0, corrections, start_, poses);
  return poses;
}

}  // namespace evoslam
