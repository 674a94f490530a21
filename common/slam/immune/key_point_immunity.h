#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_KEY_POINT_IMMUNITY_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_KEY_POINT_IMMUNITY_H_

#include <Eigen/Core>
#include <optional>

#include "common/optim/immunity.h"

namespace evoslam {

class TrajectoryWindowProblem;

// 004's immunity for SLAM (§3.3-3.4). Vaccination picks a key point of the window and one of its
// sightings; when the sighted gap, placed by the candidate's poses, does not fall in the key
// point's cell (shifted by the candidate's offset genes), it sets the length correction of the
// segment that carries the sighting's scan to the whole unit that brings the gap nearest the key
// point. Immune selection keeps the vaccinated candidate when the f1 of a grid built from that
// segment and the next alone is lower than the original's, and otherwise with probability
// `accept_worse`: two local grids of two segments each cost about 4/N of an evaluation of N
// segments.
class KeyPointImmunity : public Immunity {
 public:
  KeyPointImmunity(const TrajectoryWindowProblem& problem, double key_cell_size,
                   double accept_worse);

  bool Vaccinate(Eigen::Ref<Eigen::VectorXd> x, Rng& rng) const override;
  bool Accept(const Eigen::Ref<const Eigen::VectorXd>& original,
              const Eigen::Ref<const Eigen::VectorXd>& vaccinated, Rng& rng) const override;

  // The window's segment whose correction moves scan `scan` relative to the window's start: the
  // one that ends at or after it; nullopt for the window's first scan, which no gene moves.
  std::optional<std::size_t> SegmentMoving(std::size_t scan) const;

 private:
  const TrajectoryWindowProblem& problem_;
  double key_cell_size_;
  double accept_worse_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_KEY_POINT_IMMUNITY_H_
