#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_CORRECTION_GENES_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_CORRECTION_GENES_H_

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "common/optim/problem.h"
#include "common/slam/immune/trajectory_segments.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// How a chromosome holds a window's corrections (004 §3.2): genes 2j and 2j + 1 are segment j's
// length and turn corrections in units of length_unit_m and turn_unit_deg, within
// +-max_length_correction_m and +-max_turn_correction_deg; after them, two genes per key point of
// the window, its offset in key point cells along x and y, in {-1, 0, 1} (004 eq. 4). The integer
// encoding rounds every gene to a whole unit (004's grid); the continuous one keeps corrections
// real.
class CorrectionGenes {
 public:
  CorrectionGenes(const proto::TrajectorySegmentParams& params, std::size_t segments,
                  std::size_t key_points);

  std::size_t segments() const { return segments_; }
  std::size_t key_points() const { return key_points_; }
  std::size_t dimension() const { return 2 * segments_ + 2 * key_points_; }
  Encoding encoding() const { return encoding_; }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }

  // Segment j's correction.
  SegmentCorrection Correction(const Eigen::Ref<const Eigen::VectorXd>& x, std::size_t j) const;
  // All segments' corrections, into `out` (segments() of them).
  void Corrections(const Eigen::Ref<const Eigen::VectorXd>& x,
                   std::span<SegmentCorrection> out) const;
  // Key point i's offset, in key point cells.
  Eigen::Vector2d KeyPointOffset(const Eigen::Ref<const Eigen::VectorXd>& x, std::size_t i) const;
  // The gene of segment j's length correction.
  static std::size_t LengthGene(std::size_t j) { return 2 * j; }

 private:
  std::size_t segments_;
  std::size_t key_points_;
  Encoding encoding_;
  double length_unit_;  // m a length gene's unit is worth
  double turn_unit_;    // rad a turn gene's unit is worth
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_CORRECTION_GENES_H_
