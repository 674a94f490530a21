#include "common/slam/immune/key_point_immunity.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/slam/immune/trajectory_window_problem.h"

namespace evoslam {

KeyPointImmunity::KeyPointImmunity(const TrajectoryWindowProblem& problem, double key_cell_size,
                                   double accept_worse)
    : problem_(problem), key_cell_size_(key_cell_size), accept_worse_(accept_worse) {}

std::optional<std::size_t> KeyPointImmunity::SegmentMoving(std::size_t scan) const {
  const TrajectoryWindow& w = problem_.window();
  const auto& segments = w.trajectory->segments();
  for (std::size_t j = 0; j < w.segments; ++j) {
    const TrajectorySegment& s = segments[w.first_segment + j];
    if (s.first < scan && scan <= s.last) return j;
  }
  return std::nullopt;
}

bool KeyPointImmunity::Vaccinate(Eigen::Ref<Eigen::VectorXd> x, Rng& rng) const {
  const TrajectoryWindow& w = problem_.window();
  if (w.key_points.empty()) return false;
  const std::size_t i = rng.UniformIndex(w.key_points.size());
  const WindowKeyPoint& key = w.key_points[i];
  if (key.sightings.empty()) return false;
  const KeyPointSighting& sighting = key.sightings[rng.UniformIndex(key.sightings.size())];
  const std::optional<std::size_t> j = SegmentMoving(sighting.scan);
  if (!j) return false;

  std::vector<Pose2> poses(problem_.last_scan() - problem_.first_scan() + 1);
  const auto gap_at = [&](const Eigen::Ref<const Eigen::VectorXd>& genes) {
    problem_.Poses(genes, poses);
    return Eigen::Vector2d(poses[sighting.scan - problem_.first_scan()] * sighting.point);
  };
  const Eigen::Vector2d target =
      key.position + key_cell_size_ * problem_.genes().KeyPointOffset(x, i);
  const Eigen::Vector2d gap = gap_at(x);
  const Eigen::Vector2d miss = target - gap;
  if (miss.cwiseAbs().maxCoeff() <= key_cell_size_ / 2) return false;  // it falls in the cell

  // How the gap moves per unit of the length gene; the poses are linear in it to first order.
  const auto gene = static_cast<Eigen::Index>(CorrectionGenes::LengthGene(*j));
  Eigen::VectorXd probe = x;
  const double step = x[gene] < problem_.upper()[gene] ? 1.0 : -1.0;
  probe[gene] += step;
  const Eigen::Vector2d per_unit = (gap_at(probe) - gap) / step;
  const double moves = per_unit.squaredNorm();
  if (!(moves > 0.0)) return false;
  double value = x[gene] + per_unit.dot(miss) / moves;
  if (problem_.encoding() == Encoding::kInteger) value = std::round(value);
  value = std::clamp(value, problem_.lower()[gene], problem_.upper()[gene]);
  if (value == x[gene]) return false;
  x[gene] = value;
  return true;
}

bool KeyPointImmunity::Accept(const Eigen::Ref<const Eigen::VectorXd>& original,
                              const Eigen::Ref<const Eigen::VectorXd>& vaccinated, Rng& rng) const {
  Eigen::Index changed = 0;
  while (changed < original.size() && original[changed] == vaccinated[changed]) ++changed;
  if (changed == original.size()) return true;
  const auto segment = static_cast<std::size_t>(changed / 2);
  if (segment >= problem_.genes().segments()) return true;  // a key point offset: no map changes
  const double before = problem_.LocalConsistency(original, segment);
  const double after = problem_.LocalConsistency(vaccinated, segment);
  return after < before || rng.Uniform() < accept_worse_;
}

}  // namespace evoslam
