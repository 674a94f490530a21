#include "common/slam/immune/correction_genes.h"

#include <cmath>
#include <numbers>

namespace evoslam {

CorrectionGenes::CorrectionGenes(const proto::TrajectorySegmentParams& params, std::size_t segments,
                                 std::size_t key_points)
    : segments_(segments),
      key_points_(key_points),
      encoding_(params.encoding() == "integer" ? Encoding::kInteger : Encoding::kReal),
      length_unit_(params.length_unit_m()),
      turn_unit_(params.turn_unit_deg() * std::numbers::pi / 180.0),
      lower_(dimension()),
      upper_(dimension()) {
  // The integer encoding's bounds are whole units, inside the stated maxima.
  const auto bound = [&](double units) {
    return encoding_ == Encoding::kInteger ? std::floor(units + 1e-9) : units;
  };
  const double length_bound = bound(params.max_length_correction_m() / params.length_unit_m());
  const double turn_bound = bound(params.max_turn_correction_deg() / params.turn_unit_deg());
  for (std::size_t j = 0; j < segments_; ++j) {
    lower_[static_cast<Eigen::Index>(2 * j)] = -length_bound;
    upper_[static_cast<Eigen::Index>(2 * j)] = length_bound;
    lower_[static_cast<Eigen::Index>(2 * j + 1)] = -turn_bound;
    upper_[static_cast<Eigen::Index>(2 * j + 1)] = turn_bound;
  }
  lower_.tail(static_cast<Eigen::Index>(2 * key_points_)).setConstant(-1.0);
  upper_.tail(static_cast<Eigen::Index>(2 * key_points_)).setConstant(1.0);
}

SegmentCorrection CorrectionGenes::Correction(const Eigen::Ref<const Eigen::VectorXd>& x,
                                              std::size_t j) const {
  return {.length = x[static_cast<Eigen::Index>(2 * j)] * length_unit_,
          .turn = x[static_cast<Eigen::Index>(2 * j + 1)] * turn_unit_};
}

void CorrectionGenes::Corrections(const Eigen::Ref<const Eigen::VectorXd>& x,
                                  std::span<SegmentCorrection> out) const {
  for (std::size_t j = 0; j < segments_; ++j) out[j] = Correction(x, j);
}

Eigen::Vector2d CorrectionGenes::KeyPointOffset(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                std::size_t i) const {
  const auto gene = static_cast<Eigen::Index>(2 * segments_ + 2 * i);
  return {x[gene], x[gene + 1]};
}

}  // namespace evoslam
