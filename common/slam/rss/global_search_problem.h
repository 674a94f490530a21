#ifndef EVOSLAM_COMMON_SLAM_RSS_GLOBAL_SEARCH_PROBLEM_H_
#define EVOSLAM_COMMON_SLAM_RSS_GLOBAL_SEARCH_PROBLEM_H_

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "common/grid/hit_count_grid.h"
#include "common/optim/problem.h"
#include "common/sensor/laser_scan.h"
#include "common/slam/loop_detector.h"
#include "common/transform/pose2.h"
#include "common/transform/pose2_frame.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// The most partitions a global search may have (the command line's flag takes the same bound).
inline constexpr std::size_t kMaxPartitions = 100000;

// Paper 002's global search (§3.2); what each parameter does is in
// proto/evoslam/slam_params.proto and docs/methods/rss.md.
using GlobalSearchParams = proto::RssGlobalSearch;

// Bounds of a partition's total error per axis (m, m, rad), and eq. 5's Gaussian widths per axis
// as shares of a partition's length.
Eigen::Vector3d PartitionErrorBounds(const GlobalSearchParams& params);
Eigen::Vector3d GaussianWidths(const GlobalSearchParams& params);
// The bounds of a search without a loop (m, m, rad), which a loop's search adds to its own.
Eigen::Vector3d RefineBounds(const GlobalSearchParams& params);

void ValidateGlobalSearchParams(const GlobalSearchParams& params);

// The global search's problem over the poses of scans [first, last). The steps between them
// are split into L partitions; a candidate holds per partition and axis an error and the mean of
// a Gaussian (genes: L columns of (dx, mu_x, dy, mu_y, dtheta, mu_theta)), the error being spread
// over the partition's steps with the Gaussian's weights (eq. 5, normalised so that a
// partition's error is its total). Two objectives, both minimised: eq. 6 negated (the mean
// number of observations per occupied cell of the whole map, every beam_stride-th return of
// scored_scans evenly spaced scans of [first, last) re-inserted at their corrected poses into
// `base`, which holds every scan outside the stretch), and eq. 7 negated (w1 x the corrected
// poses that stand on an occupied cell + w2 x how far the loop's later pose lands from where the
// constraint puts it and how far its returns turn from where it puts them; no loop, no second
// term).
class GlobalSearchProblem : public Problem {
 public:
  // `poses` holds the current poses of scans [0, last). The pose of scan max(first, 1) - 1 is
  // the anchor the corrected steps start from. `max_error` bounds each partition's error (m, m,
  // rad).
  GlobalSearchProblem(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                      std::size_t first, std::size_t last, const HitCountGrid& base,
                      const GlobalSearchParams& params, const Eigen::Vector3d& max_error,
                      std::optional<LoopConstraint> loop);

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
  Eigen::Vector3d widths_;  // eq. 5's, per axis
  double occupied_pose_weight_, loop_miss_weight_;
  std::optional<LoopConstraint> loop_;
  std::optional<Observation> observed_;  // the loop's
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
// `min_eq6_gain` of its score, or it lowers eq. 7.
bool WorthApplying(std::span<const double, 2> before, std::span<const double, 2> after,
                   double min_eq6_gain);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_RSS_GLOBAL_SEARCH_PROBLEM_H_
