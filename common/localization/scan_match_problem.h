#ifndef EVOSLAM_COMMON_LOCALIZATION_SCAN_MATCH_PROBLEM_H_
#define EVOSLAM_COMMON_LOCALIZATION_SCAN_MATCH_PROBLEM_H_

#include "common/localization/range_renderer.h"
#include "common/localization/scan_fitness.h"
#include "common/optim/problem.h"
#include "common/transform/pose2.h"

namespace evoslam {

// The 2D estimator's problem: the optimiser searches (x, y) in a square window; for each
// candidate one fan of rays is simulated and every heading of the window is scored by shifting
// the observed beams along it (brute force over heading).
class ShiftedScanProblem : public Problem {
 public:
  ShiftedScanProblem(const RangeRenderer& renderer, const FitnessParams& fitness,
                     const ShiftLayout& layout, ObservedBeams observed, float max_range,
                     const Pose2& center, double window);

  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

  // The full pose (best heading) and fitness at a position.
  Pose2 PoseAt(const Eigen::Vector2d& position, double* fitness = nullptr) const;

 private:
  ShiftScore Score(const Eigen::Vector2d& position, std::span<float> rays,
                   std::span<float> sums) const;

  const RangeRenderer& renderer_;
  FitnessParams fitness_;
  ShiftLayout layout_;
  ObservedBeams observed_;
  float max_range_;
  double center_heading_;
  RayFan fan_;
  Eigen::VectorXd lower_, upper_;
};

// The 3D estimator's problem: the optimiser searches (x, y, heading) directly and each candidate
// simulates the scan at its own heading.
class PoseScanProblem : public Problem {
 public:
  PoseScanProblem(const RangeRenderer& renderer, const FitnessParams& fitness,
                  const LaserScan& scan, ObservedBeams observed, float max_range,
                  const Pose2& center, double window, double heading_half_window);

  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

 private:
  double Score(const Eigen::Ref<const Eigen::VectorXd>& x, RayFan& rotated,
               std::span<float> rays) const;

  const RangeRenderer& renderer_;
  FitnessParams fitness_;
  ObservedBeams observed_;
  float max_range_;
  RayFan beams_;  // the scan's beam directions at heading 0
  Eigen::VectorXd lower_, upper_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_SCAN_MATCH_PROBLEM_H_
