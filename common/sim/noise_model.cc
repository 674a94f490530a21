#include "common/sim/noise_model.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

void CheckNonNegative(std::string_view name, double value) {
  if (!IsFiniteNonNegative(value)) {
    throw Error(fmt::format("noise: {} must be a finite number >= 0, got {}", name, value));
  }
}

}  // namespace

void CheckNoiseModel(const NoiseModel& noise) {
  CheckNonNegative("uniform bandwidth", noise.uniform_bandwidth);
  CheckNonNegative("gaussian sigma", noise.gaussian_sigma);
  CheckNonNegative("quantization", noise.quantization);
  if (noise.pedestrians < 0) {
    throw Error(fmt::format("noise: pedestrians must be >= 0, got {}", noise.pedestrians));
  }
  CheckNonNegative("pedestrian radius", noise.pedestrian_radius);
  if (noise.pedestrian_radius == 0.0) throw Error("noise: pedestrian radius must be > 0");
  CheckNonNegative("pedestrian speed", noise.pedestrian_speed);
  CheckNonNegative("odometry translation sigma", noise.odometry.translation_sigma);
  CheckNonNegative("odometry rotation sigma", noise.odometry.rotation_sigma);
  if (!std::isfinite(noise.odometry.translation_bias) ||
      !std::isfinite(noise.odometry.rotation_bias)) {
    throw Error("noise: odometry biases must be finite");
  }
}

double NoisyRange(double range, double max_range, const NoiseModel& noise, Rng& rng) {
  if (!(range < max_range)) return max_range;
  double reading = range;
  if (noise.uniform_bandwidth > 0.0) {
    reading += noise.uniform_bandwidth * (rng.Uniform() - 0.5);
  }
  if (noise.gaussian_sigma > 0.0) reading += noise.gaussian_sigma * rng.Normal();
  if (noise.quantization > 0.0) {
    reading = std::round(reading / noise.quantization) * noise.quantization;
  }
  return std::clamp(reading, 0.0, max_range);
}

Pose2 NoisyOdometryIncrement(const Pose2& increment, const OdometryNoise& noise, Rng& rng) {
  const double scale = 1.0 + noise.translation_bias + noise.translation_sigma * rng.Normal();
  const double turn = 1.0 + noise.rotation_sigma * rng.Normal();
  const double distance = increment.translation().norm();
  return Pose2(scale * increment.translation(),
               turn * increment.theta() + noise.rotation_bias * distance);
}

}  // namespace evoslam
