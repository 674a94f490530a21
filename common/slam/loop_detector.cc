#include "common/slam/loop_detector.h"

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
}  // namespace

void ValidateLoopDetectionParams(const LoopDetectionParams& p) {
  if (!(p.revisit_radius_m() > 0.0)) throw Error("loops.revisit_radius_m: must be > 0");
  if (p.min_gap_scans() == 0) throw Error("loops.min_gap_scans: must be >= 1");
  if (p.check_interval_scans() == 0) throw Error("loops.check_interval_scans: must be >= 1");
  if (!(p.min_travel_m() >= 0.0)) throw Error("loops.min_travel_m: must not be negative");
  if (!(p.match_window_m() > 0.0) || !(p.match_window_rad() > 0.0))
    throw Error("loops.match_window_m and loops.match_window_rad: must be positive");
  if (!(p.min_match_score() > 0.0 && p.min_match_score() <= 1.0))
    throw Error("loops.min_match_score: must be in (0, 1]");
  if (!(p.min_distinctness() >= 0.0 && p.min_distinctness() <= 1.0))
    throw Error("loops.min_distinctness: must be in [0, 1]");
  if (!IsFiniteNonNegative(p.match_window_per_m()))
    throw Error("loops.match_window_per_m: must be finite and not negative");
  if (!(p.max_match_window_m() >= p.match_window_m()) || !std::isfinite(p.max_match_window_m()))
    throw Error("loops.max_match_window_m: must be finite and at least loops.match_window_m");
  if (!(p.rival_distance_m() > 0.0 && p.rival_distance_m() < p.match_window_m()))
    throw Error("loops.rival_distance_m: must be positive and below loops.match_window_m");
  if (!(p.fit_tolerance_m() >= 0.0) || !(p.fit_tolerance_rad() >= 0.0))
    throw Error("loops.fit_tolerance_m and loops.fit_tolerance_rad: must not be negative");
  if (!(p.fit_score_margin() >= 0.0 && p.fit_score_margin() <= 1.0))
    throw Error("loops.fit_score_margin: must be in [0, 1]");
  if (!(p.min_side_agreement() >= 0.0 && p.min_side_agreement() <= 1.0))
    throw Error("loops.min_side_agreement: must be in [0, 1]");
}

bool FitsWhereItIs(const Pose2& shift, const LoopDetectionParams& params) {
  return shift.translation().norm() <= params.fit_tolerance_m() &&
         std::abs(shift.theta()) <= params.fit_tolerance_rad();
}

double MatchWindow(const LoopDetectionParams& params, double travelled) {
  // min/max rather than std::clamp: unvalidated bounds give a window, not undefined behaviour.
  return std::min(params.max_match_window_m(),
                  std::max(params.match_window_m(), params.match_window_per_m() * travelled));
}

std::optional<LoopClosure> DetectLoop(std::span<const LaserScan> scans,
                                      std::span<const Pose2> poses, std::size_t current,
                                      const LoopDetectionParams& params) {
  if (current >= poses.size() || current >= scans.size()) {
    throw Error("loop detection: scan " + std::to_string(current) + " has no pose");
  }
  if (current < params.min_gap_scans()) return std::nullopt;
  const Eigen::Vector2d here = poses[current].translation();

  // The closest earlier pose within the radius, at least min_gap scans and min_travel metres
  // back along the path; the longer that path, the wider the radius and the window.
  const std::size_t newest = current - params.min_gap_scans();
  double travelled = 0.0;
  for (std::size_t k = current; k > newest; --k) {
    travelled += (poses[k].translation() - poses[k - 1].translation()).norm();
  }
  std::optional<std::size_t> earlier;
  double closest = std::numeric_limits<double>::infinity();
  double window = params.match_window_m();
  for (std::size_t j = newest + 1; j-- > 0;) {
    if (j < newest) travelled += (poses[j + 1].translation() - poses[j].translation()).norm();
    if (travelled < params.min_travel_m()) continue;
    const double d = (poses[j].translation() - here).norm();
    const double window_j = MatchWindow(params, travelled);
    if (d < closest && d < params.revisit_radius_m() + window_j - params.match_window_m()) {
      closest = d;
      earlier = j;
      window = window_j;
    }
  }
  if (!earlier) return std::nullopt;

  // The earlier place's map: scans around it, none from the recent path.
  const std::size_t place_scans = params.place_scans();
  const std::size_t lo = *earlier > place_scans ? *earlier - place_scans : 0;
  const std::size_t hi = std::min(*earlier + place_scans + 1, newest + 1);
  const PlaceMatcher place(scans.subspan(lo, hi - lo), poses.subspan(lo, hi - lo), kFieldResolution,
                           kFieldSigma, window);
  const std::vector<Eigen::Vector2d> points = ReturnPoints(scans[current]);
  const PlaceMatcher::Match match = place.Search(
      points, poses[current], window, params.match_window_rad(), params.rival_distance_m());
  if (match.score < params.min_match_score() || match.distinctness < params.min_distinctness()) {
    return std::nullopt;
  }
  if (FitsWhereItIs(poses[current].inverse() * match.pose, params)) return std::nullopt;
  if (params.fit_score_margin() > 0.0 &&
      place.Score(points, poses[current]) >= match.score - params.fit_score_margin()) {
    return std::nullopt;
  }
  // Last, as the dearest test: most revisits that match fit where they are.
  if (params.min_side_agreement() > 0.0 &&
      place.SideAgreement(points, match.pose) < params.min_side_agreement()) {
    return std::nullopt;
  }
  const LoopConstraint constraint{*earlier, current, poses[*earlier].inverse() * match.pose};
  return LoopClosure{constraint, match.score, match.distinctness};
}

}  // namespace evoslam
