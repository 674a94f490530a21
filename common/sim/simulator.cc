#include "common/sim/simulator.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "common/io/carmen_writer.h"
#include "common/io/text_fields.h"
#include "common/io/text_file_writer.h"
#include "common/line_map/line_map.h"
#include "common/sim/crowd.h"
#include "common/sim/trajectory.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"
#include "common/util/random.h"

namespace evoslam {
namespace {

// Independent random streams, so that turning one disturbance on or off leaves the others'
// draws unchanged.
enum Stream : std::uint64_t { kOdometryStream = 1, kRangeStream = 2, kCrowdStream = 3 };

void CheckOptions(const SimulationOptions& options) {
  CheckLaserModel(options.laser);
  CheckNoiseModel(options.noise);
  if (!IsFiniteNonNegative(options.step)) {
    throw Error(fmt::format("simulation: step must be a finite number >= 0, got {}", options.step));
  }
  if (!IsFinitePositive(options.scan_interval)) {
    throw Error(fmt::format("simulation: scan interval must be a positive number, got {}",
                            options.scan_interval));
  }
}

}  // namespace

double RoutePoseCount(const World& world, const SimulationOptions& options) {
  double length = 0.0;
  for (std::size_t i = 1; i < world.waypoints.size(); ++i) {
    length += (world.waypoints[i] - world.waypoints[i - 1]).norm();
  }
  const double step = options.step > 0.0 ? options.step : world.scan_spacing;
  return std::floor(length / step) + 1.0;
}

Dataset Simulate(const World& world, const SimulationOptions& options) {
  CheckOptions(options);
  const double step = options.step > 0.0 ? options.step : world.scan_spacing;
  // The whole route is laid out before max_scans cuts it, so a step too fine for memory must be
  // refused before it is.
  if (const double poses = RoutePoseCount(world, options); !(poses <= kMaxSimulatedScans)) {
    throw Error(fmt::format(
        "simulation: a step of {} m makes {:.0f} poses of world \"{}\"'s route, more than {:.0f}",
        step, poses, world.name, kMaxSimulatedScans));
  }
  std::vector<Pose2> route = RouteTrajectory(world, step);
  if (options.max_scans > 0 && route.size() > options.max_scans) route.resize(options.max_scans);

  const LaserModel& laser = options.laser;
  const NoiseModel& noise = options.noise;
  const Rng base(options.seed);
  Rng odometry_rng = base.Stream(kOdometryStream);
  Rng range_rng = base.Stream(kRangeStream);
  Rng crowd_rng = base.Stream(kCrowdStream);
  std::optional<Crowd> crowd;
  if (noise.pedestrians > 0) {
    crowd.emplace(world.map, noise.pedestrians, noise.pedestrian_radius, noise.pedestrian_speed,
                  crowd_rng);
  }

  Dataset dataset;
  dataset.source = "simulated world " + world.name;
  // FLASER lines do not carry the maximum range; CARMEN logs state it as a PARAM.
  dataset.params.emplace_back("robot_front_laser_max", FormatShortest(laser.max_range));
  dataset.scans.reserve(route.size());
  dataset.odometry.reserve(route.size());
  Pose2 odometry = route.front();
  for (std::size_t i = 0; i < route.size(); ++i) {
    const Pose2& truth = route[i];
    const double time = kSimulationEpoch + static_cast<double>(i) * options.scan_interval;
    Pose2 moved;  // this step's odometry increment
    if (i > 0) {
      moved = NoisyOdometryIncrement(route[i - 1].inverse() * truth, noise.odometry, odometry_rng);
      odometry = odometry * moved;
      if (crowd) crowd->Advance(world.map, options.scan_interval, crowd_rng);
    }

    LaserScan scan;
    scan.timestamp = time;
    scan.logger_timestamp = time;
    scan.message = LaserMessage::kFront;
    scan.angle_min = laser.angle_min();
    scan.angle_increment = laser.angle_increment();
    scan.range_min = laser.min_range;
    scan.range_max = laser.max_range;
    scan.pose = odometry;
    scan.odometry = odometry;
    scan.true_pose = truth;
    scan.ranges.resize(static_cast<std::size_t>(laser.beams));
    for (int b = 0; b < laser.beams; ++b) {
      const double angle = truth.theta() + laser.angle(b);
      double range = world.map.CastRay(truth.translation(), angle, laser.max_range);
      if (crowd) range = std::min(range, crowd->CastRay(truth.translation(), angle, range));
      scan.ranges[b] = static_cast<float>(NoisyRange(range, laser.max_range, noise, range_rng));
    }
    dataset.scans.push_back(std::move(scan));

    OdometryReading reading;
    reading.timestamp = time;
    reading.logger_timestamp = time;
    reading.pose = odometry;
    reading.tv = moved.translation().norm() / options.scan_interval;
    reading.rv = moved.theta() / options.scan_interval;
    dataset.odometry.push_back(reading);
  }
  return dataset;
}

void WriteSimulation(const Dataset& dataset, const World& world, const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw Error(fmt::format("{}: cannot create directory: {}", dir.string(), error.message()));
  }
  const std::filesystem::path truth_path = dir / "truth.txt";
  TextFileWriter truth(truth_path);
  for (std::size_t i = 0; i < dataset.scans.size(); ++i) {
    const LaserScan& scan = dataset.scans[i];
    if (!scan.true_pose) {
      throw Error(fmt::format("{}: scan {} has no true pose", truth_path.string(), i));
    }
    const Pose2& p = *scan.true_pose;
    truth.Write(
        fmt::format("{:.6f} {:.6f} {:.6f} {:.6f}\n", scan.timestamp, p.x(), p.y(), p.theta()));
  }
  truth.Close();
  WriteLineMap(world.map, dir / "world.lines");
  WriteCarmen(dataset, dir / "log.clf");
}

}  // namespace evoslam
