#include "common/slam/loop_detector.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/slam/place_matcher.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

constexpr double kFieldResolution = 0.05;  // m
constexpr double kFieldSigma = 0.1;        // m: a few cells, so the coarse lattice sees the peak
// The variance of a uniform error over the coarse lattice's step (two cells): the least a spread
// can say about a direction.
constexpr double kLatticeVariance = (2 * kFieldResolution) * (2 * kFieldResolution) / 12.0;

}  // namespace

void ValidateLoopDetectionParams(const LoopDetectionParams& p) {
  if (!(p.revisit_radius > 0.0)) throw Error("loop detection: the revisit radius must be > 0");
  if (p.min_gap == 0) throw Error("loop detection: the gap between visits must be >= 1 scan");
  if (p.check_interval == 0) throw Error("loop detection: the check interval must be >= 1 scan");
  if (!(p.min_travel >= 0.0)) throw Error("loop detection: the travel must not be negative");
  if (!(p.match_window > 0.0) || !(p.match_window_theta > 0.0))
    throw Error("loop detection: the match window must be positive");
  if (!(p.min_score > 0.0 && p.min_score <= 1.0))
    throw Error("loop detection: the match score threshold must be in (0, 1]");
  if (!(p.min_distinctness >= 0.0 && p.min_distinctness <= 1.0))
    throw Error("loop detection: the distinctness threshold must be in [0, 1]");
  if (!IsFiniteNonNegative(p.match_window_per_metre))
    throw Error("loop detection: the window's growth per metre must be finite and not negative");
  if (!(p.max_match_window >= p.match_window) || !std::isfinite(p.max_match_window))
    throw Error("loop detection: the largest match window must be finite and at least the window");
  if (!(p.rival_distance > 0.0 && p.rival_distance < p.match_window))
    throw Error("loop detection: the rival distance must be positive and within the match window");
  if (!(p.fit_tolerance >= 0.0) || !(p.fit_tolerance_theta >= 0.0))
    throw Error("loop detection: the fit tolerances must not be negative");
  if (!(p.fit_score_margin >= 0.0 && p.fit_score_margin <= 1.0))
    throw Error("loop detection: the fit's score margin must be in [0, 1]");
  if (!(p.min_side_agreement >= 0.0 && p.min_side_agreement <= 1.0))
    throw Error(
        "loop detection: the share of returns seen from the place's side must be in [0, 1]");
  if (!IsFiniteNonNegative(p.spread_score))
    throw Error("loop detection: the spread's score scale must be finite and not negative");
}

Eigen::Matrix2d LoopWeight(const Eigen::Matrix2d& spread, double heading) {
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(-heading).toRotationMatrix();
  const Eigen::Matrix2d covariance =
      r * spread * r.transpose() + kLatticeVariance * Eigen::Matrix2d::Identity();
  const double a = covariance(0, 0), b = 0.5 * (covariance(0, 1) + covariance(1, 0));
  const double c = covariance(1, 1);
  const double smallest = 0.5 * (a + c - std::hypot(a - c, 2.0 * b));
  // The inverse written out, so that the weight is exactly symmetric.
  Eigen::Matrix2d weight;
  weight << c, -b, -b, a;
  return smallest / (a * c - b * b) * weight;
}

bool FitsWhereItIs(const Pose2& shift, double heading, const Eigen::Matrix2d& weight,
                   const LoopDetectionParams& params) {
  return WeightedLength(shift.translation(), heading, weight) <= params.fit_tolerance &&
         std::abs(shift.theta()) <= params.fit_tolerance_theta;
}

double MatchWindow(const LoopDetectionParams& params, double travelled) {
  // min/max rather than std::clamp: unvalidated bounds give a window, not undefined behaviour.
  return std::min(params.max_match_window,
                  std::max(params.match_window, params.match_window_per_metre * travelled));
}

std::optional<LoopClosure> DetectLoop(std::span<const LaserScan> scans,
                                      std::span<const Pose2> poses, std::size_t current,
                                      const LoopDetectionParams& params) {
  if (current >= poses.size() || current >= scans.size()) {
    throw Error("loop detection: scan " + std::to_string(current) + " has no pose");
  }
  if (current < params.min_gap) return std::nullopt;
  const Eigen::Vector2d here = poses[current].translation();

  // The closest earlier pose within the radius, at least min_gap scans and min_travel metres
  // back along the path; the longer that path, the wider the radius and the window.
  const std::size_t newest = current - params.min_gap;
  double travelled = 0.0;
  for (std::size_t k = current; k > newest; --k) {
    travelled += (poses[k].translation() - poses[k - 1].translation()).norm();
  }
  std::optional<std::size_t> earlier;
  double closest = std::numeric_limits<double>::infinity();
  double window = params.match_window;
  for (std::size_t j = newest + 1; j-- > 0;) {
    if (j < newest) travelled += (poses[j + 1].translation() - poses[j].translation()).norm();
    if (travelled < params.min_travel) continue;
    const double d = (poses[j].translation() - here).norm();
    const double window_j = MatchWindow(params, travelled);
    if (d < closest && d < params.revisit_radius + window_j - params.match_window) {
      closest = d;
      earlier = j;
      window = window_j;
    }
  }
  if (!earlier) return std::nullopt;

  // The earlier place's map: scans around it, none from the recent path.
  const std::size_t lo = *earlier > params.place_scans ? *earlier - params.place_scans : 0;
  const std::size_t hi = std::min(*earlier + params.place_scans + 1, newest + 1);
  const PlaceMatcher place(scans.subspan(lo, hi - lo), poses.subspan(lo, hi - lo), kFieldResolution,
                           kFieldSigma, window);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(scans[current]);
  const PlaceMatcher::Match match =
      place.Search(points, poses[current], window, params.match_window_theta, params.rival_distance,
                   params.spread_score);
  if (match.score < params.min_score || match.distinctness < params.min_distinctness) {
    return std::nullopt;
  }

  const Eigen::Matrix2d weight = params.spread_score > 0.0
                                     ? LoopWeight(match.spread, poses[*earlier].theta())
                                     : Eigen::Matrix2d::Identity();
  // The shift is in the current scan's frame; the weight, in the earlier scan's.
  const Pose2 shift = poses[current].inverse() * match.pose;
  if (FitsWhereItIs(shift, poses[*earlier].theta() - poses[current].theta(), weight, params)) {
    return std::nullopt;
  }
  if (params.fit_score_margin > 0.0 &&
      place.Score(points, poses[current]) >= match.score - params.fit_score_margin) {
    return std::nullopt;
  }
  // Last, as the dearest test: most revisits that match fit where they are.
  if (params.min_side_agreement > 0.0 &&
      place.SideAgreement(points, match.pose) < params.min_side_agreement) {
    return std::nullopt;
  }
  LoopConstraint constraint{*earlier, current, poses[*earlier].inverse() * match.pose};
  if (params.spread_weights_eq7) constraint.weight = weight;
  return LoopClosure{constraint, match.score, match.distinctness};
}

}  // namespace evoslam
