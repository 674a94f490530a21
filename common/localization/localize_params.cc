#include "common/localization/localize_params.h"

#include <string>

#include "common/engine/engine_proto.h"
#include "common/optim/differential_evolution.h"
#include "common/optim/particle_swarm.h"
#include "common/transform/angle_units.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

std::string OptimizerName(const EstimatorParams& e) {
  switch (e.optimizer) {
    case OptimizerKind::kAlgorithm:
      return std::string(AlgorithmKindName(e.algorithm.kind));
    case OptimizerKind::kIsland:
      return "island";
    case OptimizerKind::kExhaustive:
      return "exhaustive";
  }
  return {};
}

}  // namespace

proto::LocalizeParams ToProto(const LocalizeOptions& options) {
  const EstimatorParams& e = options.estimator;
  proto::LocalizeParams p;
  p.set_fitness(std::string(FitnessKindName(e.fitness.kind)));
  p.set_f2_base_m(e.fitness.f2_base);
  p.set_f2_slope(e.fitness.f2_slope);
  p.set_f3_cap_m(e.fitness.f3_cap);
  p.set_estimator(std::string(EstimatorKindName(e.estimator)));
  p.set_optimizer(OptimizerName(e));
  p.set_strategy(std::string(DeStrategyName(e.algorithm.de.strategy)));
  p.set_population(static_cast<std::uint32_t>(PopulationSize(e.algorithm)));
  p.set_generations(static_cast<std::uint32_t>(e.generations));
  p.set_f(e.algorithm.de.f);
  p.set_cr(e.algorithm.de.cr);
  p.set_pso_inertia(e.algorithm.pso.inertia);
  p.set_pso_c1(e.algorithm.pso.c1);
  p.set_pso_c2(e.algorithm.pso.c2);
  p.set_pso_vmax_fraction(e.algorithm.pso.vmax_fraction);
  p.set_pso_neighbourhood(std::string(PsoNeighbourhoodName(e.algorithm.pso.neighbourhood)));
  *p.mutable_algorithm() = evoslam::ToProto(e.algorithm);
  if (e.optimizer == OptimizerKind::kIsland) {
    p.set_islands(static_cast<std::uint32_t>(e.islands));
    p.set_island_algorithm(std::string(AlgorithmKindName(e.algorithm.kind)));
    p.set_migration_interval(static_cast<std::uint32_t>(e.migration.interval));
    p.set_migrants(static_cast<std::uint32_t>(e.migration.migrants));
    p.set_topology(std::string(TopologyName(e.migration.topology)));
    p.set_migration_policy(std::string(MigrationPolicyName(e.migration.policy)));
  }
  p.set_window_m(e.window);
  p.set_heading_window_deg(Degrees(e.heading_half_window));
  p.set_heading_step_deg(Degrees(e.heading_step));
  p.set_heading_window_rad(e.heading_half_window);
  p.set_heading_step_rad(e.heading_step);
  p.set_exhaustive_step_m(e.exhaustive_step);
  p.set_use_odometry(options.use_odometry);
  p.set_seed(options.seed);
  p.set_max_range_m(options.max_range);
  p.set_max_scans(static_cast<std::uint32_t>(options.max_scans));
  if (options.start) {
    for (double v : {options.start->x(), options.start->y(), options.start->theta()})
      p.add_start(v);
  }
  return p;
}

LocalizeOptions LocalizeOptionsFromProto(const proto::LocalizeParams& p) {
  LocalizeOptions options;
  EstimatorParams& e = options.estimator;
  e.fitness.kind = ParseFitnessKind(p.fitness());
  if (p.has_f2_base_m()) e.fitness.f2_base = p.f2_base_m();
  if (p.has_f2_slope()) e.fitness.f2_slope = p.f2_slope();
  e.fitness.f3_cap = p.f3_cap_m();
  e.estimator = ParseEstimatorKind(p.estimator());
  e.optimizer = ParseOptimizer(p.optimizer(), e.algorithm);
  if (!p.has_algorithm()) throw Error("localize parameters: the algorithm settings are missing");
  e.algorithm = FromProto(p.algorithm());
  e.generations = p.generations();
  if (e.optimizer == OptimizerKind::kIsland) {
    e.islands = p.islands();
    e.migration.interval = p.migration_interval();
    e.migration.migrants = p.migrants();
    e.migration.topology = ParseTopology(p.topology());
    e.migration.policy = ParseMigrationPolicy(p.migration_policy());
  }
  e.window = p.window_m();
  e.heading_half_window = p.heading_window_rad();
  e.heading_step = p.heading_step_rad();
  e.exhaustive_step = p.exhaustive_step_m();
  ValidateEstimatorParams(e);
  options.use_odometry = p.use_odometry();
  options.seed = p.seed();
  if (!(p.max_range_m() >= 0.0)) throw Error("localize parameters: max range must be >= 0");
  options.max_range = p.max_range_m();
  options.max_scans = p.max_scans();
  if (p.start_size() == 3) {
    options.start = Pose2(p.start(0), p.start(1), p.start(2));
  } else if (p.start_size() != 0) {
    throw Error("localize parameters: start needs x, y and theta, got " +
                std::to_string(p.start_size()) + " values");
  }
  return options;
}

}  // namespace evoslam
