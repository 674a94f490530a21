#ifndef EVOSLAM_COMMON_EVAL_TRAJECTORY_ERRORS_H_
#define EVOSLAM_COMMON_EVAL_TRAJECTORY_ERRORS_H_

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "common/io/relations.h"
#include "common/io/trajectory_io.h"

namespace evoslam {

// Finds poses by timestamp. Relations and ground truth refer to scans by their ipc_timestamp,
// which logs print with microseconds; a match must lie within `tolerance` seconds.
class TrajectoryIndex {
 public:
  explicit TrajectoryIndex(std::span<const StampedPose> trajectory, double tolerance = 1e-4);
  std::optional<Pose2> At(double timestamp) const;

 private:
  std::vector<StampedPose> sorted_;
  double tolerance_;
};

// Absolute errors against ground truth, paired by timestamp: root mean square error per axis and
// in heading (eq. 9 of the L1/L2 comparative study), and of the translation, all in the truth's
// frame as the estimate stands. A SLAM run fixes its frame by its first pose, so an error in its
// first steps shifts or turns everything after; `aligned_rms_translation` leaves that out.
struct AbsoluteErrors {
  std::size_t poses = 0;      // poses paired
  std::size_t unmatched = 0;  // estimated poses with no truth at their timestamp
  double rms_x = 0.0;         // m
  double rms_y = 0.0;         // m
  double rms_theta = 0.0;     // rad
  double rms_translation = 0.0;
  double max_translation = 0.0;
  // The absolute trajectory error of SLAM benchmarks (Sturm et al. 2012): the RMS translation
  // error once the estimate's positions are moved by the rotation and translation that bring
  // them closest to the truth's in the least-squares sense (Horn 1987), m.
  double aligned_rms_translation = 0.0;
  // The same once a uniform scale is also allowed (Umeyama 1991), and that scale: the factor the
  // estimate's positions are multiplied by to fit the truth's. A map drawn uniformly too long,
  // as where odometry over-reads down a corridor the scans do not measure, is wrong by a scale
  // that no loop reveals; this error is what is left besides it.
  double scale_aligned_rms_translation = 0.0;
  double alignment_scale = 1.0;
};
AbsoluteErrors ComputeAbsoluteErrors(std::span<const StampedPose> estimate,
                                     std::span<const StampedPose> truth);

// Kuemmerle et al. (2009): for each relation R between times t1 and t2, the error
// E = (P(t1)^-1 P(t2)) R^-1; mean and standard deviation of |translation(E)| and |angle(E)|,
// and of their squares.
struct RelationErrors {
  std::size_t relations = 0;  // relations evaluated
  std::size_t skipped = 0;    // relations whose times the trajectory does not cover
  double translation_mean = 0.0, translation_std = 0.0;        // m
  double rotation_mean = 0.0, rotation_std = 0.0;              // rad
  double translation_sq_mean = 0.0, translation_sq_std = 0.0;  // m^2
  double rotation_sq_mean = 0.0, rotation_sq_std = 0.0;        // rad^2
};
RelationErrors ComputeRelationErrors(std::span<const StampedPose> trajectory,
                                     std::span<const Relation> relations);

// Relations between consecutive ground-truth poses, to measure relative error where a simulation
// gives truth instead of a relations file.
std::vector<Relation> RelationsFromTruth(std::span<const StampedPose> truth);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_EVAL_TRAJECTORY_ERRORS_H_
