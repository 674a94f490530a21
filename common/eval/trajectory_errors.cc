#include "common/eval/trajectory_errors.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace evoslam {

TrajectoryIndex::TrajectoryIndex(std::span<const StampedPose> trajectory, double tolerance)
    : sorted_(trajectory.begin(), trajectory.end()), tolerance_(tolerance) {
  std::stable_sort(sorted_.begin(), sorted_.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp < b.timestamp;
  });
}

std::optional<Pose2> TrajectoryIndex::At(double timestamp) const {
  const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), timestamp,
                                   [](const StampedPose& p, double t) { return p.timestamp < t; });
  const StampedPose* best = nullptr;
  if (it != sorted_.end()) best = &*it;
  if (it != sorted_.begin()) {
    const StampedPose* before = &*(it - 1);
    if (!best || timestamp - before->timestamp < best->timestamp - timestamp) best = before;
  }
  if (!best || std::abs(best->timestamp - timestamp) > tolerance_) return std::nullopt;
  return best->pose;
}

namespace {

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

MeanStd Moments(const std::vector<double>& v) {
  MeanStd m;
  if (v.empty()) return m;
  for (double x : v) m.mean += x;
  m.mean /= static_cast<double>(v.size());
  for (double x : v) m.std += (x - m.mean) * (x - m.mean);
  m.std = std::sqrt(m.std / static_cast<double>(v.size()));
  return m;
}

struct Alignments {
  double rigid_rms = 0.0;
  double scaled_rms = 0.0;
  double scale = 1.0;
};

// The RMS distance between `estimated` and `truth`, paired by index, after the rigid motion of
// `estimated` that minimises it, and after the similarity (a rigid motion and a uniform scale)
// that does (Umeyama 1991). In 2D both have a closed form: the rotation is the angle of the
// summed cross and dot products of the centred pairs, the scale their length over the estimate's
// spread.
Alignments Align(std::span<const Eigen::Vector2d> estimated,
                 std::span<const Eigen::Vector2d> truth) {
  const auto n = static_cast<double>(estimated.size());
  Eigen::Vector2d mean_e = Eigen::Vector2d::Zero(), mean_t = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < estimated.size(); ++i) {
    mean_e += estimated[i];
    mean_t += truth[i];
  }
  mean_e /= n;
  mean_t /= n;
  double dot = 0.0, cross = 0.0, spread = 0.0;
  for (std::size_t i = 0; i < estimated.size(); ++i) {
    const Eigen::Vector2d a = estimated[i] - mean_e, b = truth[i] - mean_t;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
    spread += a.squaredNorm();
  }
  Alignments result;
  // An estimate with no spread has no scale to find; the rigid figures stand for both.
  if (spread > 0.0) result.scale = std::hypot(dot, cross) / spread;
  const Eigen::Rotation2Dd rotation(std::atan2(cross, dot));
  double rigid = 0.0, scaled = 0.0;
  for (std::size_t i = 0; i < estimated.size(); ++i) {
    const Eigen::Vector2d turned = rotation * (estimated[i] - mean_e), target = truth[i] - mean_t;
    rigid += (turned - target).squaredNorm();
    scaled += (result.scale * turned - target).squaredNorm();
  }
  result.rigid_rms = std::sqrt(rigid / n);
  result.scaled_rms = std::sqrt(scaled / n);
  return result;
}

}  // namespace

AbsoluteErrors ComputeAbsoluteErrors(std::span<const StampedPose> estimate,
                                     std::span<const StampedPose> truth) {
  const TrajectoryIndex index(truth);
  AbsoluteErrors e;
  double sx = 0, sy = 0, st = 0;
  std::vector<Eigen::Vector2d> estimated, true_positions;
  for (const StampedPose& p : estimate) {
    const auto t = index.At(p.timestamp);
    if (!t) {
      ++e.unmatched;
      continue;
    }
    estimated.push_back(p.pose.translation());
    true_positions.push_back(t->translation());
    const double dx = p.pose.x() - t->x();
    const double dy = p.pose.y() - t->y();
    const double dt = WrapAngle(p.pose.theta() - t->theta());
    sx += dx * dx;
    sy += dy * dy;
    st += dt * dt;
    e.max_translation = std::max(e.max_translation, std::hypot(dx, dy));
    ++e.poses;
  }
  if (e.poses > 0) {
    const auto n = static_cast<double>(e.poses);
    e.rms_x = std::sqrt(sx / n);
    e.rms_y = std::sqrt(sy / n);
    e.rms_theta = std::sqrt(st / n);
    e.rms_translation = std::sqrt((sx + sy) / n);
    const Alignments a = Align(estimated, true_positions);
    e.aligned_rms_translation = a.rigid_rms;
    e.scale_aligned_rms_translation = a.scaled_rms;
    e.alignment_scale = a.scale;
  }
  return e;
}

RelationErrors ComputeRelationErrors(std::span<const StampedPose> trajectory,
                                     std::span<const Relation> relations) {
  const TrajectoryIndex index(trajectory);
  std::vector<double> trans, rot, trans_sq, rot_sq;
  RelationErrors e;
  for (const Relation& r : relations) {
    const auto p1 = index.At(r.t1);
    const auto p2 = index.At(r.t2);
    if (!p1 || !p2) {
      ++e.skipped;
      continue;
    }
    const Pose2 error = (p1->inverse() * *p2) * r.delta.inverse();
    const double t = error.translation().norm();
    const double a = std::abs(error.theta());
    trans.push_back(t);
    rot.push_back(a);
    trans_sq.push_back(t * t);
    rot_sq.push_back(a * a);
  }
  e.relations = trans.size();
  const MeanStd mt = Moments(trans), mr = Moments(rot), mt2 = Moments(trans_sq),
                mr2 = Moments(rot_sq);
  e.translation_mean = mt.mean;
  e.translation_std = mt.std;
  e.rotation_mean = mr.mean;
  e.rotation_std = mr.std;
  e.translation_sq_mean = mt2.mean;
  e.translation_sq_std = mt2.std;
  e.rotation_sq_mean = mr2.mean;
  e.rotation_sq_std = mr2.std;
  return e;
}

std::vector<Relation> RelationsFromTruth(std::span<const StampedPose> truth) {
  std::vector<Relation> relations;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    relations.push_back(
        {truth[i - 1].timestamp, truth[i].timestamp, truth[i - 1].pose.inverse() * truth[i].pose});
  }
  return relations;
}

}  // namespace evoslam
