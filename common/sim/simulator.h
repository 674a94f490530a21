#ifndef EVOSLAM_COMMON_SIM_SIMULATOR_H_
#define EVOSLAM_COMMON_SIM_SIMULATOR_H_

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "common/sensor/dataset.h"
#include "common/sim/laser_model.h"
#include "common/sim/noise_model.h"
#include "common/sim/world.h"

namespace evoslam {

// Timestamp of the first simulated scan, seconds.
inline constexpr double kSimulationEpoch = 1e9;

struct SimulationOptions {
  LaserModel laser = {};
  NoiseModel noise = {};
  double step = 0.0;           // metres driven between scans; 0: the world's scan_spacing
  double scan_interval = 0.2;  // seconds between scans
  std::size_t max_scans = 0;   // 0: the whole route
  std::uint64_t seed = 1;
};

// The most scans a simulation makes, or poses its route takes, at once.
inline constexpr double kMaxSimulatedScans = 1e6;

// How many poses the route of `world` takes at the options' step, counted before any is made.
double RoutePoseCount(const World& world, const SimulationOptions& options);

// Drives the world's route and logs a scan every `step` metres, as a raw robot log would hold
// it: scan i at kSimulationEpoch + i * scan_interval, with its true pose, the drifting odometry
// (also as the scan's stated pose) and ranges cast from the true pose with the noise model
// applied; plus one ODOM reading per scan. The same options and seed give the same dataset.
// Throws Error for invalid options, a route of more than kMaxSimulatedScans poses, or a route
// that comes too close to a wall.
Dataset Simulate(const World& world, const SimulationOptions& options);

// Writes dir/log.clf (CARMEN, with TRUEPOS), dir/world.lines (the walls) and dir/truth.txt
// ("t x y theta" per scan), creating dir if needed. Throws Error naming the path on failure.
void WriteSimulation(const Dataset& dataset, const World& world, const std::filesystem::path& dir);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SIM_SIMULATOR_H_
