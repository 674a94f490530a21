#ifndef EVOSLAM_COMMON_SLAM_LOOP_DETECTOR_H_
#define EVOSLAM_COMMON_SLAM_LOOP_DETECTOR_H_

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>

#include "common/sensor/laser_scan.h"
#include "common/slam/global_search_problem.h"
#include "common/transform/pose2.h"

namespace evoslam {

// When the robot is back in a place it has mapped and its scan does not fit the map there: the
// rule that starts a loop-closing global search (docs/rss_slam.md).
struct LoopDetectionParams {
  // A revisit: the current pose lies within this distance of an earlier pose...
  double revisit_radius = 2.0;  // m
  // ...that is at least this many scans and this much travelled path back.
  std::size_t min_gap = 100;
  double min_travel = 8.0;  // m
  // The scan is matched against the earlier place's map (the scans within place_scans of the
  // earlier one) inside this window around where the trajectory puts it.
  std::size_t place_scans = 25;
  double match_window = 1.5;         // m, half-width
  double match_window_theta = 0.35;  // rad, half-width
  // Drift grows with the path between the two visits: the window widens to this fraction of
  // that path, up to max_match_window, and the revisit radius grows with it. ACES's long loops
  // come back 2 to 4 m off along its corridors (docs/rss_slam.md).
  double match_window_per_metre = 0.02;
  double max_match_window = 5.0;  // m
  // The match is trusted when this fraction of the scan's returns land near the place's
  // obstacles (the likelihood score's mean, 0 to 1)...
  double min_score = 0.8;
  // ...and it stands out: its score exceeds the best at least rival_distance away by at least
  // min_distinctness (docs/rss_slam.md)...
  double min_distinctness = 0.05;
  double rival_distance = 0.3;  // m
  // Above 0, a loop's match weighs its miss by direction, in eq. 7 and in the fit test below: a
  // lattice pose whose score is this much below the best counts 1/e as much in the match's
  // spread (PlaceMatcher::Match), and a miss along a direction the spread is long in counts for
  // little. 0 (the default): every direction counts the same, as in 002; weighting was no
  // better on the real logs (docs/accuracy-history.md).
  double spread_score = 0.0;
  // With spread_score above 0, false weighs the fit test alone: a shift along a corridor the match
  // cannot pin is not taken as drift, and the loops found are closed as 002 closes them.
  bool spread_weights_eq7 = true;
  // ...and the scan does not fit where the trajectory puts it when the match moves it further
  // than this. A place seen across a corridor and revisited along it pulls the match 10 to 15 cm
  // along the corridor (docs/rss_slam.md): a shift within that is the match's error, not drift.
  double fit_tolerance = 0.15;        // m
  double fit_tolerance_theta = 0.02;  // rad
  // ...nor when the pose the trajectory gives the scan scores within this much of the match
  // (PlaceMatcher::Score, 0 to 1): the trajectory already explains the scan about as well, and a
  // shift the score barely tells apart is the match's noise. With a noisy or sparse laser such
  // matches land farther from the truth than the trajectory had the scan (docs/rss_slam.md).
  // 0: off.
  double fit_score_margin = 0.025;
  // ...nor when fewer than this share of the match's returns that land near the place's obstacles
  // see them from the side the place saw them (PlaceMatcher::SideAgreement): a pose inside a block
  // whose faces it lines up, or in the next room through a wall, is a look-alike. Such a match
  // agrees at 0.02 to 0.03, the real logs' loops at 0.5 to 1 (docs/rss_slam.md). 0: off.
  double min_side_agreement = 0.25;
  // Scans after a detection before the next one may be reported.
  std::size_t cooldown = 100;
  // A revisit is checked at every this many scans: matching costs milliseconds, and the robot
  // stays in a revisited place for many scans.
  std::size_t check_interval = 10;
};

void ValidateLoopDetectionParams(const LoopDetectionParams& params);

// The match window's half-width (m) for a revisit `travelled` metres of path after the earlier
// visit; the revisit radius is revisit_radius plus what this adds to match_window.
double MatchWindow(const LoopDetectionParams& params, double travelled);

// Eq. 7's weight of a loop (LoopConstraint::weight) from its match's spread (world frame), in
// the frame of an earlier pose at `heading`: the inverse of the spread plus the lattice's own
// variance, scaled so that its largest eigenvalue is 1.
Eigen::Matrix2d LoopWeight(const Eigen::Matrix2d& spread, double heading);

// Whether a scan that its match moves by `shift` (in the scan's frame) already fits where the
// trajectory puts it: within fit_tolerance_theta, and within fit_tolerance as `weight`, given in
// a frame turned by `heading` from the scan's, measures the translation (WeightedLength).
// Measured as eq. 7 measures the loop's miss, a loop that a search closed as far as its match
// pins it down is not found again at the next check.
bool FitsWhereItIs(const Pose2& shift, double heading, const Eigen::Matrix2d& weight,
                   const LoopDetectionParams& params);

// A place seen twice, found by matching.
struct LoopClosure {
  LoopConstraint constraint;
  double score = 0.0;         // the match's likelihood score, 0 to 1
  double distinctness = 0.0;  // how far the match stands out (PlaceMatcher::Match)
};

// Checks scan `current` (its pose poses[current]) against the places the trajectory passed
// before; poses holds the poses of scans [0, current]. Returns the loop when the scan is a
// revisit of an earlier place whose match is trusted and does not fit the trajectory.
std::optional<LoopClosure> DetectLoop(std::span<const LaserScan> scans,
                                      std::span<const Pose2> poses, std::size_t current,
                                      const LoopDetectionParams& params);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_LOOP_DETECTOR_H_
