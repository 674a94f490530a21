#include "common/slam/rss/scan_refinement.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "common/transform/pose2_frame.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

// An eigenvalue of the normal matrix this small beside the largest counts as a direction the
// returns do not constrain: rounding, not geometry.
constexpr double kUnconstrained = 1e-9;

// The sums of one Gauss-Newton step at a pose.
struct Normal {
  double cost = 0.0;  // sum of squared residuals
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
};

Normal NormalEquations(const HitCountGrid& map, std::span<const Eigen::Vector2d> returns,
                       const Pose2& pose, double wall_share) {
  const Pose2Frame frame(pose);
  Normal n;
  for (const Eigen::Vector2d& p : returns) {
    const Eigen::Vector2d q = frame * p;
    const auto s = SampleOccupancy(map, q, wall_share);
    if (!s) continue;
    const double r = 1.0 - s->value;
    const Eigen::Vector2d arm = q - pose.translation();
    const Eigen::Vector3d j(s->gradient.x(), s->gradient.y(),
                            s->gradient.y() * arm.x() - s->gradient.x() * arm.y());
    n.cost += r * r;
    n.h.noalias() += j * j.transpose();
    n.g.noalias() += j * r;
  }
  return n;
}

// The largest count among the four cells (x, y) to (x + 1, y + 1) and the cells around them: a
// 4 x 4 block, clipped to the grid.
double StrongestCount(const HitCountGrid& map, int x, int y) {
  std::uint32_t strongest = 0;
  for (int cy = std::max(y - 1, 0); cy <= std::min(y + 2, map.height() - 1); ++cy) {
    for (int cx = std::max(x - 1, 0); cx <= std::min(x + 2, map.width() - 1); ++cx) {
      strongest = std::max(strongest, map.count(cx, cy));
    }
  }
  return strongest;
}

// Multiplies (x, y, heading) so that all three measure how far the returns' end points move: the
// heading by the returns' mean range. The normal matrix's eigenvalues then compare. nullopt
// without returns.
std::optional<Eigen::Vector3d> CoordinateScale(std::span<const Eigen::Vector2d> returns) {
  double range = 0.0;
  for (const Eigen::Vector2d& p : returns) range += p.norm();
  if (returns.empty() || !(range > 0.0)) return std::nullopt;
  return Eigen::Vector3d(1.0, 1.0, static_cast<double>(returns.size()) / range);
}

}  // namespace

void ValidateScanRefinementParams(const ScanRefinementParams& p) {
  if (p.iterations() > 1000) throw Error("local.refine.iterations: at most 1000");
  if (!IsFiniteNonNegative(p.max_shift_cells()))
    throw Error("local.refine.max_shift_cells: must be finite and not negative");
  if (!IsFiniteNonNegative(p.max_turn_rad()))
    throw Error("local.refine.max_turn_rad: must be finite and not negative");
  if (!(p.wall_share() >= 0.0 && p.wall_share() <= 1.0))
    throw Error("local.refine.wall_share: must lie in [0, 1]");
}

std::optional<OccupancySample> SampleOccupancy(const HitCountGrid& map,
                                               const Eigen::Vector2d& point, double wall_share) {
  const Eigen::Vector2d u = (point - map.origin()) / map.resolution() - Eigen::Vector2d(0.5, 0.5);
  if (!(u.x() >= 0.0 && u.y() >= 0.0 && u.x() < map.width() - 1 && u.y() < map.height() - 1)) {
    return std::nullopt;
  }
  const int x = static_cast<int>(u.x()), y = static_cast<int>(u.y());
  const double fx = u.x() - x, fy = u.y() - y;
  // Binary with a share of 0, and where the block holds no count (then every cell reads 0).
  const double full = wall_share > 0.0 ? wall_share * StrongestCount(map, x, y) : 0.0;
  const auto level = [&](int cx, int cy) -> double {
    return full > 0.0 ? std::min(1.0, map.count(cx, cy) / full)
                      : map.occupied(map.geometry().Index(cx, cy));
  };
  const double m00 = level(x, y), m10 = level(x + 1, y);
  const double m01 = level(x, y + 1), m11 = level(x + 1, y + 1);
  OccupancySample s;
  s.value = (1 - fy) * ((1 - fx) * m00 + fx * m10) + fy * ((1 - fx) * m01 + fx * m11);
  s.gradient = Eigen::Vector2d((1 - fy) * (m10 - m00) + fy * (m11 - m01),
                               (1 - fx) * (m01 - m00) + fx * (m11 - m10)) /
               map.resolution();
  return s;
}

Eigen::Matrix3d ScanInformation(const HitCountGrid& map, std::span<const Eigen::Vector2d> returns,
                                const Pose2& pose, double wall_share) {
  return NormalEquations(map, returns, pose, wall_share).h;
}

RefinedPose RefineScanPose(const HitCountGrid& map, std::span<const Eigen::Vector2d> returns,
                           const Pose2& start, const ScanRefinementParams& params) {
  // The offset from `start` is kept apart from the pose, whose heading wraps at pi.
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  const auto moved = [&start](const Eigen::Vector3d& d) {
    return Pose2(start.x() + d.x(), start.y() + d.y(), start.theta() + d.z());
  };
  const std::optional<Eigen::Vector3d> scale = CoordinateScale(returns);
  if (!scale) return {start, Eigen::Matrix3d::Zero()};
  const double max_shift = params.max_shift_cells() * map.resolution();
  Normal at = NormalEquations(map, returns, start, params.wall_share());
  for (std::size_t it = 0; it < params.iterations(); ++it) {
    const Eigen::Matrix3d h = scale->asDiagonal() * at.h * scale->asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(h);
    if (eigen.info() != Eigen::Success) break;
    const Eigen::Vector3d& values = eigen.eigenvalues();  // ascending
    if (!(values(2) > 0.0)) break;
    // The step solves the normal equations in the directions the returns constrain; along one
    // they do not (two parallel walls and nothing else), it stays 0 rather than divide by 0.
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    const Eigen::Vector3d g = scale->asDiagonal() * at.g;
    for (int k = 0; k < 3; ++k) {
      if (values(k) > kUnconstrained * values(2)) {
        step += eigen.eigenvectors().col(k) * (eigen.eigenvectors().col(k).dot(g) / values(k));
      }
    }
    Eigen::Vector3d next = offset + scale->asDiagonal() * step;
    if (!next.allFinite()) break;
    const double shift = next.head<2>().norm();
    if (shift > max_shift) next.head<2>() *= max_shift / shift;
    next.z() = std::clamp(next.z(), -params.max_turn_rad(), params.max_turn_rad());
    const Normal there = NormalEquations(map, returns, moved(next), params.wall_share());
    if (!(there.cost < at.cost)) break;
    offset = next;
    at = there;
  }
  return {moved(offset), at.h};
}

Pose2 KeepPriorWhereUnconstrained(const Eigen::Matrix3d& information,
                                  std::span<const Eigen::Vector2d> returns, const Pose2& pose,
                                  const Pose2& prior, double min_ratio, double prior_weight) {
  const std::optional<Eigen::Vector3d> scale = CoordinateScale(returns);
  if ((!(min_ratio > 0.0) && !(prior_weight > 0.0)) || !scale) return pose;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scale->asDiagonal() * information *
                                                             scale->asDiagonal());
  if (eigen.info() != Eigen::Success) return pose;
  const Eigen::Vector3d& values = eigen.eigenvalues();  // ascending
  if (!(values(2) > 0.0)) return prior;
  // Every direction constrained and the prior weightless: the pose as it is, not rebuilt through
  // the eigenvectors.
  if (!(prior_weight > 0.0) && values(0) >= min_ratio * values(2)) return pose;
  // The offset in the scaled coordinates the eigenvectors live in, projected onto the constrained
  // ones (the ascending eigenvalues put the unconstrained first).
  const Eigen::Vector3d offset = scale->cwiseInverse().asDiagonal() *
                                 Eigen::Vector3d(pose.x() - prior.x(), pose.y() - prior.y(),
                                                 WrapAngle(pose.theta() - prior.theta()));
  Eigen::Vector3d kept = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (values(k) >= min_ratio * values(2) && values(k) > 0.0) {
      const double share = values(k) / values(2);
      const double weight = share / (share + prior_weight);  // exactly 1 without a prior weight
      kept += eigen.eigenvectors().col(k) * (eigen.eigenvectors().col(k).dot(offset) * weight);
    }
  }
  kept = scale->asDiagonal() * kept;
  return Pose2(prior.x() + kept.x(), prior.y() + kept.y(), prior.theta() + kept.z());
}

}  // namespace evoslam
