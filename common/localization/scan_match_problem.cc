#include "common/localization/scan_match_problem.h"

#include <vector>

namespace evoslam {

ShiftedScanProblem::ShiftedScanProblem(const RangeRenderer& renderer, const FitnessParams& fitness,
                                       const ShiftLayout& layout, ObservedBeams observed,
                                       float max_range, const Pose2& center, double window)
    : renderer_(renderer),
      fitness_(fitness),
      layout_(layout),
      observed_(std::move(observed)),
      max_range_(max_range),
      center_heading_(center.theta()),
      fan_(center.theta() + layout.first_offset, layout.ray_step, layout.rays),
      lower_(center.translation().array() - 0.5 * window),
      upper_(center.translation().array() + 0.5 * window) {}

ShiftScore ShiftedScanProblem::Score(const Eigen::Vector2d& position, std::span<float> rays,
                                     std::span<float> sums) const {
  renderer_.Render(position, fan_, max_range_, rays);
  return BestShift(fitness_, layout_, observed_, rays, max_range_, sums);
}

void ShiftedScanProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                                  std::span<double> fitness) const {
  const Eigen::Index n = candidates.cols();
#pragma omp parallel
  {
    std::vector<float> rays(layout_.rays);
    std::vector<float> sums(layout_.shifts);
#pragma omp for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) {
      fitness[static_cast<std::size_t>(i)] = Score(candidates.col(i), rays, sums).fitness;
    }
  }
}

Pose2 ShiftedScanProblem::PoseAt(const Eigen::Vector2d& position, double* fitness) const {
  std::vector<float> rays(layout_.rays);
  std::vector<float> sums(layout_.shifts);
  const ShiftScore best = Score(position, rays, sums);
  if (fitness) *fitness = best.fitness;
  return Pose2(position, center_heading_ + layout_.shift_angle(best.shift));
}

PoseScanProblem::PoseScanProblem(const RangeRenderer& renderer, const FitnessParams& fitness,
                                 const LaserScan& scan, ObservedBeams observed, float max_range,
                                 const Pose2& center, double window, double heading_half_window)
    : renderer_(renderer),
      fitness_(fitness),
      observed_(std::move(observed)),
      max_range_(max_range),
      beams_(scan.angle_min, scan.angle_increment, scan.size()),
      lower_(3),
      upper_(3) {
  lower_ << center.x() - 0.5 * window, center.y() - 0.5 * window,
      center.theta() - heading_half_window;
  upper_ << center.x() + 0.5 * window, center.y() + 0.5 * window,
      center.theta() + heading_half_window;
}

double PoseScanProblem::Score(const Eigen::Ref<const Eigen::VectorXd>& x, RayFan& rotated,
                              std::span<float> rays) const {
  beams_.RotatedInto(x(2), rotated);
  renderer_.Render(x.head<2>(), rotated, max_range_, rays);
  return ScoreAligned(fitness_, observed_, rays, max_range_);
}

void PoseScanProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                               std::span<double> fitness) const {
  const Eigen::Index n = candidates.cols();
#pragma omp parallel
  {
    RayFan rotated;
    std::vector<float> rays(beams_.size());
#pragma omp for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) {
      fitness[static_cast<std::size_t>(i)] = Score(candidates.col(i), rotated, rays);
    }
  }
}

}  // namespace evoslam
