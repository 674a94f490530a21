#include "common/grid/grid_geometry.h"

#include <string>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {

GridGeometry::GridGeometry(double resolution, const Eigen::Vector2d& origin, int width, int height)
    : origin_(origin), resolution_(resolution), width_(width), height_(height) {
  if (!IsFinitePositive(resolution)) {
    throw Error("grid: resolution must be a positive number of metres, got " +
                std::to_string(resolution));
  }
  if (!origin.allFinite()) throw Error("grid: origin must be finite");
  if (width <= 0 || height <= 0) {
    throw Error("grid: size " + std::to_string(width) + " x " + std::to_string(height) +
                " must be positive");
  }
}

Eigen::Vector2d GridGeometry::max_corner() const {
  return origin_ + resolution_ * Eigen::Vector2d(width_, height_);
}

}  // namespace evoslam
