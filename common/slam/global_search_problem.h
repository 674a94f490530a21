#ifndef EVOSLAM_COMMON_SLAM_GLOBAL_SEARCH_PROBLEM_H_
#define EVOSLAM_COMMON_SLAM_GLOBAL_SEARCH_PROBLEM_H_

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "common/grid/hit_count_grid.h"
#include "common/optim/problem.h"
#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"
#include "common/transform/pose2_frame.h"

namespace evoslam {

// Paper 002's global search (§3.2) settings.
// The most partitions a global search may have (the command line's flag takes the same bound).
inline constexpr std::size_t kMaxPartitions = 100000;

struct GlobalSearchParams {
  std::size_t partitions = 8;  // L
  // Bounds of a partition's total error per axis (m, m, rad).
  Eigen::Vector3d max_error{1.0, 1.0, 0.3};
  // The Gaussian of eq. 5 per axis, as a fraction of a partition's length.
  Eigen::Vector3d sigma{0.3, 0.3, 0.3};
  // Eq. 7: weight of each corrected pose that stands on an occupied cell (002 Fig. 11: 0.5). The
  // term is a count and the loop's a length: w1 / w2 is the metres of loop miss one such pose is
  // worth, a metre with 002's weights (docs/accuracy-history.md has smaller ones measured).
  double w1 = 0.5;
  // Eq. 7: weight of the distance between two observations of one place: how far the loop's
  // later scan lands from where the match puts it, its heading's miss counted by how far it
  // moves the scan's returns (docs/rss_slam.md).
  double w2 = 0.5;
  // Eq. 6 counts every this-many-th return of each scan of the stretch. Neighbouring scans see
  // the same walls, so half the returns still draw them, at 0.6 of the cost (docs/rss_slam.md).
  std::size_t beam_stride = 2;
  // Eq. 6 re-inserts at most this many scans of the stretch, evenly spaced (0: every scan), so
  // that a search over a whole loop of thousands of steps costs what one over a few hundred
  // does; the poses of every step still count in eq. 7 (docs/rss_slam.md).
  std::size_t scored_scans = 300;
};

void ValidateGlobalSearchParams(const GlobalSearchParams& params);

// A place seen twice: scan `later` should sit at `relative` in scan `earlier`'s frame.
struct LoopConstraint {
  std::size_t earlier = 0;
  std::size_t later = 0;
  Pose2 relative;
  // Eq. 7 measures how far `later` lands from there, d in `earlier`'s frame, as sqrt(d' W d).
  // W's largest eigenvalue is 1: the identity gives 002's distance, and a match that only pins
  // the place across a corridor gives a W that barely counts a miss along it.
  Eigen::Matrix2d weight = Eigen::Matrix2d::Identity();
};

// How long a loop's `weight` finds a miss d (world frame) in the frame of a pose at `heading`:
// sqrt(d' W d), d turned into that frame. The identity gives d's plain length, computed as such,
// so that 002's distance comes out the same bits. Eq. 7 and the loop detector's fit test both
// measure a loop's miss with it.
double WeightedLength(const Eigen::Vector2d& miss, double heading, const Eigen::Matrix2d& weight);

// The global search's problem over the poses of scans [first, last). The steps between them
// are split into L partitions; a candidate holds per partition and axis an error and the mean of
// a Gaussian (genes: L columns of (dx, mu_x, dy, mu_y, dtheta, mu_theta)), the error being spread
// over the partition's steps with the Gaussian's weights (eq. 5, normalised so that a
// partition's error is its total). Two objectives, both minimised: eq. 6 negated (the mean
// number of observations per occupied cell of the whole map, every beam_stride-th return of
// scored_scans evenly spaced scans of [first, last) re-inserted at their corrected poses into
// `base`, which holds every scan outside the stretch), and eq. 7 negated (w1 x the corrected
// poses that stand on an occupied cell + w2 x how far the loop's later pose lands from where the
// constraint puts it, as its weight measures it, and how far its returns turn from where it puts
// them, summed over the loop and the `held` loops, those found before whose later scan lies in
// [first, last); no constraint, no second term).
class GlobalSearchProblem : public Problem {
 public:
  // `poses` holds the current poses of scans [0, last). The pose of scan max(first, 1) - 1 is
  // the anchor the corrected steps start from.
  GlobalSearchProblem(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                      std::size_t first, std::size_t last, const HitCountGrid& base,
                      const GlobalSearchParams& params, std::optional<LoopConstraint> loop,
                      std::span<const LoopConstraint> held = {});

  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  std::size_t objectives() const override { return 2; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

  // The corrected poses of scans [first, last) for a candidate.
  std::vector<Pose2> Apply(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // The candidate that changes nothing (all errors zero, means centred).
  Eigen::VectorXd Identity() const;
  // The candidate that closes the loop: the heading's miss at the loop's later scan shared out
  // between the partitions at the least total correction (evenly, when the loop ends the
  // stretch), then its position's miss likewise, each gene within its bounds. Held loops that
  // start before the stretch are kept as they are, or closed, in the same least-squares sense.
  // None without a loop, or for one that starts inside the stretch.
  std::optional<Eigen::VectorXd> ClosingCandidate() const;
  // The search starts from the trajectory as it stands, and from the loop closed.
  std::vector<Eigen::VectorXd> starts() const override;

 private:
  // A thread's working memory, made once a batch rather than once a candidate.
  struct Scratch {
    GridCellSet cells;              // the cells the stretch's end points fall in
    std::vector<double> weights;    // eq. 5's weights of a partition's steps, per axis
    std::vector<Pose2Frame> poses;  // the candidate's corrected poses
  };
  void Apply(const Eigen::Ref<const Eigen::VectorXd>& x, std::vector<double>& weights,
             std::vector<Pose2Frame>& poses) const;
  void Score(const Eigen::Ref<const Eigen::VectorXd>& x, Scratch& scratch, double* fitness) const;

  // A loop eq. 7 measures, with what its distance needs besides the candidate's poses.
  struct Observation {
    LoopConstraint constraint;
    Pose2Frame earlier_pose;  // when it lies before first
    // The RMS range of the later scan: turned by a small angle, its returns move about that
    // many times the angle.
    double lever = 0.0;
  };
  Observation Observe(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                      const LoopConstraint& loop) const;
  double Distance(const Observation& o, std::span<const Pose2Frame> poses) const;

  const HitCountGrid& base_;
  GlobalSearchParams params_;
  std::optional<LoopConstraint> loop_;
  // The loop's observation first, then those of the held loops.
  std::vector<Observation> observed_;
  std::size_t first_, last_;
  std::size_t scan_stride_ = 1;         // eq. 6 re-inserts scans first, first + stride, ...
  std::size_t steps_begin_;             // the first corrected step
  Pose2Frame anchor_;                   // the pose before steps_begin_
  std::vector<Pose2Frame> increments_;  // step j's motion, j in [steps_begin_, last)
  std::vector<std::size_t> bounds_;     // partition i covers steps [bounds_[i], bounds_[i + 1])
  // The end points of scan first + k * scan_stride_, laser frame.
  std::vector<std::vector<Eigen::Vector2d>> returns_;
  Eigen::VectorXd lower_, upper_;
};

// The global search's choice among a final population (objectives x n): 002's, the individual of
// the first Pareto front with the lowest second objective (the loop closed, the path free), ties
// going to the better first; only individuals whose first objective is at most `max_first`
// compete. None when no individual does.
std::optional<std::size_t> PickGlobalSolution(
    const Eigen::MatrixXd& fitness, double max_first = std::numeric_limits<double>::infinity());

// Whether a picked correction scoring `after` (eq. 6, eq. 7 negated, as minimised) is worth
// applying to a stretch scoring `before`: it sharpens the map (eq. 6) by more than the fraction
// `min_eq6_gain` of its score, or it lowers eq. 7 by more than the fraction `min_eq7_gain` of
// what it was.
bool WorthApplying(std::span<const double, 2> before, std::span<const double, 2> after,
                   double min_eq6_gain, double min_eq7_gain);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_GLOBAL_SEARCH_PROBLEM_H_
