#ifndef EVOSLAM_COMMON_SIM_NOISE_MODEL_H_
#define EVOSLAM_COMMON_SIM_NOISE_MODEL_H_

#include "common/transform/pose2.h"
#include "common/util/random.h"

namespace evoslam {

// How odometry strays from the true motion. Each step's true increment (translation t,
// rotation r, robot frame) is read as
//   t * (1 + translation_bias + translation_sigma * n1)
//   r * (1 + rotation_sigma * n2) + rotation_bias * |t|
// with n1, n2 standard normal, and the readings are integrated, so the error grows with the
// distance driven. The defaults are a plausible wheeled indoor robot's.
struct OdometryNoise {
  double translation_sigma = 0.02;  // relative, per increment
  double rotation_sigma = 0.05;     // relative, per increment
  double translation_bias = 0.01;   // relative: the wheels over-read by 1 %
  double rotation_bias = 0.005;     // radians of heading drift per metre driven
};

// Disturbances of the simulated sensors. Range noise is applied in this order to a beam that
// met something within max_range: + U(-B/2, B/2) with B = uniform_bandwidth, + N(0, sigma^2),
// rounding to a multiple of quantization, clamping to [0, max_range]. A beam that met nothing
// reads max_range (no return) untouched. The range noise defaults to none.
struct NoiseModel {
  double uniform_bandwidth = 0.0;  // metres
  double gaussian_sigma = 0.0;     // metres
  double quantization = 0.0;       // metres; 0 keeps readings continuous
  // People walking between random free points; they hide the walls behind them.
  int pedestrians = 0;
  double pedestrian_radius = 0.25;  // metres
  double pedestrian_speed = 1.0;    // metres per second
  OdometryNoise odometry = {};
};

// Throws Error naming the offending parameter unless every parameter is finite and
// non-negative (and the pedestrian radius positive).
void CheckNoiseModel(const NoiseModel& noise);

// The reading of a beam whose true range is `range` (max_range when it met nothing).
double NoisyRange(double range, double max_range, const NoiseModel& noise, Rng& rng);

// The odometry's reading of a true increment (this step's motion in the previous pose's frame).
Pose2 NoisyOdometryIncrement(const Pose2& increment, const OdometryNoise& noise, Rng& rng);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_NOISE_MODEL_H_
