#ifndef EVOSLAM_COMMON_SLAM_RSS_STEP_CORRECTION_PROBLEM_H_
#define EVOSLAM_COMMON_SLAM_RSS_STEP_CORRECTION_PROBLEM_H_

#include <Eigen/Core>
#include <span>
#include <string_view>
#include <vector>

#include "common/grid/hit_count_grid.h"
#include "common/optim/problem.h"
#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"
#include "common/transform/pose2_frame.h"

namespace evoslam {

// Paper 002's two scores of a scan against the map (§3.1): eval1 counts the occupied cells of
// the part of the map being updated once the scan is in (eq. 1, fewer is better: the scan's
// obstacles fall on obstacles already seen); eval2 is the mean number of observations per
// occupied cell there (eq. 2, more is better).
enum class LocalFitness { kEval1, kEval2 };
LocalFitness ParseLocalFitness(std::string_view name);  // "eval1" | "eval2"
std::string_view LocalFitnessName(LocalFitness fitness);

// The local search's problem: the odometry error (dx, dy, dtheta) of the robot's last step, in
// the robot's frame at the pose odometry predicts, within +-max_error per coordinate. A
// candidate is scored by inserting the scan's returns at the corrected pose into the map. The
// part of the map being updated is the box of cells any candidate's returns can reach, so the
// scores of all candidates are taken over the same cells. Minimised: eval1 as it is, eval2
// negated. With an odometry pull p, a candidate also pays p cells' worth of score times its mean
// squared correction relative to max_error (the axes with no room pay nothing), so that of two
// corrections that fit alike the smaller wins; a cell's worth is 1 in eval1, and in eval2 what one
// more observation of an occupied cell of the window is worth. With `free_frontier`, a return on
// the edge of what the map's rays have seen adds no cell (HitCountGrid::Frontier; the map must
// track rays for that to change anything).
class StepCorrectionProblem : public Problem {
 public:
  StepCorrectionProblem(const HitCountGrid& map, const LaserScan& scan, const Pose2& predicted,
                        const Eigen::Vector3d& max_error, LocalFitness fitness,
                        double odometry_pull = 0.0, bool free_frontier = false);

  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

  // The pose a correction gives.
  Pose2 Corrected(const Eigen::Ref<const Eigen::VectorXd>& error) const;
  // One candidate's score (as Evaluate gives it).
  double Score(const Eigen::Ref<const Eigen::VectorXd>& error) const;

 private:
  // `cells`: a thread's working memory, made once a batch rather than once a candidate.
  double Score(const Eigen::Ref<const Eigen::VectorXd>& error, CellSet& cells) const;

  const HitCountGrid& map_;
  Pose2Frame predicted_;
  LocalFitness fitness_;
  bool free_frontier_;
  // The pull per axis, in score per squared unit of correction.
  Eigen::Vector3d pull_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> returns_;  // the scan's end points in the laser's frame
  HitCountGrid::WindowSums window_;       // the part of the map being updated, before the scan
  Eigen::VectorXd lower_, upper_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_RSS_STEP_CORRECTION_PROBLEM_H_
