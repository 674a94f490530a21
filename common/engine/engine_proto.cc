#include "common/engine/engine_proto.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

// Bounds a hostile message cannot push us past: a population matrix of this many values is
// already 128 MiB.
constexpr std::uint64_t kMaxMatrixValues = 16u << 20;

std::size_t Count(std::uint64_t v, const char* what) {
  if (v > std::numeric_limits<std::uint32_t>::max())
    throw Error(std::string("engine message: ") + what + " is out of range");
  return static_cast<std::size_t>(v);
}

void CheckVersion(std::uint32_t version, const char* what) {
  if (version != kEngineProtocolVersion) {
    throw Error(std::string(what) + " has protocol version " + std::to_string(version) +
                ", this build reads version " + std::to_string(kEngineProtocolVersion));
  }
}

std::optional<StopReason> ParseStopReason(const std::string& name) {
  if (name.empty()) return std::nullopt;
  for (const StopReason r :
       {StopReason::kEvaluations, StopReason::kGenerations, StopReason::kTarget,
        StopReason::kStagnation, StopReason::kWallTime, StopReason::kConverged}) {
    if (StopReasonName(r) == name) return r;
  }
  throw Error("island checkpoint: unknown stop reason '" + name + "'");
}

StopProgress FromProto(const proto::StopProgressState& p) {
  StopProgress out;
  out.best.assign(p.best().begin(), p.best().end());
  out.generations_without_improvement = Count(p.generations_without_improvement(), "stagnation");
  out.elapsed_seconds = p.elapsed_seconds();
  if (!(out.elapsed_seconds >= 0.0)) throw Error("checkpoint: elapsed time is negative or NaN");
  return out;
}

proto::StopProgressState ToProto(const StopProgress& p) {
  proto::StopProgressState out;
  for (const double b : p.best) out.add_best(b);
  out.set_generations_without_improvement(p.generations_without_improvement);
  out.set_elapsed_seconds(p.elapsed_seconds);
  return out;
}

Eigen::VectorXd Vector(const google::protobuf::RepeatedField<double>& v) {
  Eigen::VectorXd out(v.size());
  for (int i = 0; i < v.size(); ++i) out(i) = v.Get(i);
  return out;
}

proto::GaSettings ToProto(const GaParams& p) {
  proto::GaSettings out;
  out.set_population(static_cast<std::uint32_t>(p.population));
  out.set_bits(static_cast<std::uint32_t>(p.bits));
  out.set_grid_step(p.grid_step);
  out.set_crossover(std::string(GaCrossoverName(p.crossover)));
  out.set_elite_fraction(p.elite_fraction);
  out.set_pairs(static_cast<std::uint32_t>(p.pairs));
  out.set_mutants(static_cast<std::uint32_t>(p.mutants));
  out.set_mutation_box(p.mutation_box);
  out.set_replaced(static_cast<std::uint32_t>(p.replaced));
  out.set_bit_flip(p.bit_flip);
  return out;
}

GaParams FromProto(const proto::GaSettings& p) {
  GaParams out;
  out.population = p.population();
  if (p.bits() > 64) throw Error("engine message: GA bits out of range");
  out.bits = static_cast<int>(p.bits());
  out.grid_step = p.grid_step();
  out.crossover = ParseGaCrossover(p.crossover());
  out.elite_fraction = p.elite_fraction();
  out.pairs = p.pairs();
  out.mutants = p.mutants();
  out.mutation_box = p.mutation_box();
  out.replaced = p.replaced();
  out.bit_flip = p.bit_flip();
  return out;
}

}  // namespace

proto::Matrix ToProto(const Eigen::MatrixXd& m) {
  proto::Matrix out;
  out.set_rows(static_cast<std::uint32_t>(m.rows()));
  out.set_cols(static_cast<std::uint32_t>(m.cols()));
  out.mutable_values()->Add(m.data(), m.data() + m.size());
  return out;
}

Eigen::MatrixXd FromProto(const proto::Matrix& m, const char* what) {
  const std::uint64_t values = static_cast<std::uint64_t>(m.rows()) * m.cols();
  if (values > kMaxMatrixValues)
    throw Error(std::string("engine message: matrix '") + what + "' is too large");
  if (static_cast<std::uint64_t>(m.values_size()) != values) {
    throw Error(std::string("engine message: matrix '") + what + "' is " +
                std::to_string(m.rows()) + "x" + std::to_string(m.cols()) + " but holds " +
                std::to_string(m.values_size()) + " values");
  }
  Eigen::MatrixXd out(m.rows(), m.cols());
  std::copy(m.values().begin(), m.values().end(), out.data());
  return out;
}

proto::AlgorithmSettings ToProto(const AlgorithmSpec& spec) {
  proto::AlgorithmSettings out;
  switch (spec.kind) {
    case AlgorithmKind::kDe: {
      auto* de = out.mutable_de();
      de->set_strategy(std::string(DeStrategyName(spec.de.strategy)));
      de->set_population(static_cast<std::uint32_t>(spec.de.population));
      de->set_f(spec.de.f);
      de->set_cr(spec.de.cr);
      break;
    }
    case AlgorithmKind::kJde: {
      auto* j = out.mutable_jde();
      j->set_strategy(std::string(DeStrategyName(spec.jde.strategy)));
      j->set_population(static_cast<std::uint32_t>(spec.jde.population));
      j->set_tau_f(spec.jde.tau_f);
      j->set_tau_cr(spec.jde.tau_cr);
      j->set_f_lower(spec.jde.f_lower);
      j->set_f_range(spec.jde.f_range);
      j->set_f_initial(spec.jde.f_initial);
      j->set_cr_initial(spec.jde.cr_initial);
      break;
    }
    case AlgorithmKind::kPso: {
      auto* p = out.mutable_pso();
      p->set_particles(static_cast<std::uint32_t>(spec.pso.particles));
      p->set_inertia(spec.pso.inertia);
      p->set_c1(spec.pso.c1);
      p->set_c2(spec.pso.c2);
      p->set_vmax_fraction(spec.pso.vmax_fraction);
      p->set_neighbourhood(std::string(PsoNeighbourhoodName(spec.pso.neighbourhood)));
      break;
    }
    case AlgorithmKind::kSga:
      *out.mutable_sga() = ToProto(spec.ga);
      break;
    case AlgorithmKind::kAga:
      *out.mutable_aga() = ToProto(spec.ga);
      break;
    case AlgorithmKind::kMuPlusLambda: {
      const MuPlusLambdaParams& m = spec.mu_plus_lambda;
      auto* o = out.mutable_mu_plus_lambda();
      o->set_mu(static_cast<std::uint32_t>(m.mu));
      o->set_lambda(static_cast<std::uint32_t>(m.lambda));
      o->set_tournament(static_cast<std::uint32_t>(m.q));
      o->set_pc(m.pc);
      o->set_pm(m.pm);
      o->set_c(m.c);
      o->set_gene_group(static_cast<std::uint32_t>(m.gene_group));
      o->set_column(static_cast<std::uint32_t>(m.column));
      o->set_generation_limit(static_cast<std::uint32_t>(m.generation_limit));
      o->set_variance_threshold(m.variance_threshold);
      o->set_offspring_share(m.offspring_share);
      break;
    }
    case AlgorithmKind::kImmune: {
      const ImmuneMoeaParams& m = spec.immune;
      auto* o = out.mutable_immune();
      o->set_population(static_cast<std::uint32_t>(m.population));
      o->set_recombinations(static_cast<std::uint32_t>(m.recombinations));
      o->set_mutations(static_cast<std::uint32_t>(m.mutations));
      o->set_p_recombination(m.p_recombination);
      o->set_p_immunity(m.p_immunity);
      o->set_p_mutation(m.p_mutation);
      o->set_recombination(std::string(ImmuneRecombinationName(m.recombination)));
      o->set_blend_alpha(m.blend_alpha);
      o->set_restart_spread(m.restart_spread);
      o->set_archive_size(static_cast<std::uint32_t>(m.archive_size));
      break;
    }
  }
  return out;
}

AlgorithmSpec FromProto(const proto::AlgorithmSettings& settings) {
  AlgorithmSpec spec;
  switch (settings.kind_case()) {
    case proto::AlgorithmSettings::kDe: {
      const auto& de = settings.de();
      spec.kind = AlgorithmKind::kDe;
      spec.de.strategy = ParseDeStrategy(de.strategy());
      spec.de.population = de.population();
      spec.de.f = de.f();
      spec.de.cr = de.cr();
      break;
    }
    case proto::AlgorithmSettings::kJde: {
      const auto& j = settings.jde();
      spec.kind = AlgorithmKind::kJde;
      spec.jde.strategy = ParseDeStrategy(j.strategy());
      spec.jde.population = j.population();
      spec.jde.tau_f = j.tau_f();
      spec.jde.tau_cr = j.tau_cr();
      spec.jde.f_lower = j.f_lower();
      spec.jde.f_range = j.f_range();
      spec.jde.f_initial = j.f_initial();
      spec.jde.cr_initial = j.cr_initial();
      break;
    }
    case proto::AlgorithmSettings::kPso: {
      const auto& p = settings.pso();
      spec.kind = AlgorithmKind::kPso;
      spec.pso.particles = p.particles();
      spec.pso.inertia = p.inertia();
      spec.pso.c1 = p.c1();
      spec.pso.c2 = p.c2();
      spec.pso.vmax_fraction = p.vmax_fraction();
      spec.pso.neighbourhood = ParsePsoNeighbourhood(p.neighbourhood());
      break;
    }
    case proto::AlgorithmSettings::kSga:
      spec.kind = AlgorithmKind::kSga;
      spec.ga = FromProto(settings.sga());
      break;
    case proto::AlgorithmSettings::kAga:
      spec.kind = AlgorithmKind::kAga;
      spec.ga = FromProto(settings.aga());
      break;
    case proto::AlgorithmSettings::kMuPlusLambda: {
      const auto& o = settings.mu_plus_lambda();
      spec.kind = AlgorithmKind::kMuPlusLambda;
      MuPlusLambdaParams& m = spec.mu_plus_lambda;
      m.mu = o.mu();
      m.lambda = o.lambda();
      m.q = o.tournament();
      m.pc = o.pc();
      m.pm = o.pm();
      m.c = o.c();
      m.gene_group = o.gene_group();
      m.column = o.column();
      m.generation_limit = o.generation_limit();
      m.variance_threshold = o.variance_threshold();
      m.offspring_share = o.offspring_share();
      break;
    }
    case proto::AlgorithmSettings::kImmune: {
      const auto& o = settings.immune();
      spec.kind = AlgorithmKind::kImmune;
      ImmuneMoeaParams& m = spec.immune;
      m.population = o.population();
      m.recombinations = o.recombinations();
      m.mutations = o.mutations();
      m.p_recombination = o.p_recombination();
      m.p_immunity = o.p_immunity();
      m.p_mutation = o.p_mutation();
      m.recombination = ParseImmuneRecombination(o.recombination());
      m.blend_alpha = o.blend_alpha();
      m.restart_spread = o.restart_spread();
      m.archive_size = o.archive_size();
      break;
    }
    default:
      throw Error("engine message: no algorithm, or one this build does not know");
  }
  // A hostile message could ask for billions of individuals; nothing evoslam runs needs more
  // than a million a batch.
  constexpr std::size_t kMaxIndividuals = 1u << 20;
  const std::size_t batch =
      std::max({PopulationSize(spec), spec.mu_plus_lambda.lambda,
                spec.immune.recombinations + spec.immune.mutations, spec.immune.archive_size});
  if (PopulationSize(spec) > kMaxIndividuals ||
      (spec.kind == AlgorithmKind::kMuPlusLambda && batch > kMaxIndividuals) ||
      (spec.kind == AlgorithmKind::kImmune && batch > kMaxIndividuals)) {
    throw Error("engine message: more than " + std::to_string(kMaxIndividuals) +
                " individuals asked for");
  }
  MakeAlgorithm(spec);  // validates the parameters
  return spec;
}

proto::StopSettings ToProto(const StopCriteria& stop) {
  proto::StopSettings out;
  out.set_max_evaluations(stop.max_evaluations);
  out.set_max_generations(stop.max_generations);
  out.set_has_target(stop.target.has_value());
  out.set_target(stop.target.value_or(0.0));
  out.set_stagnation_generations(stop.stagnation_generations);
  out.set_wall_seconds(stop.wall_seconds);
  return out;
}

StopCriteria FromProto(const proto::StopSettings& stop) {
  StopCriteria out;
  out.max_evaluations = static_cast<std::size_t>(stop.max_evaluations());
  out.max_generations = static_cast<std::size_t>(stop.max_generations());
  if (stop.has_target()) out.target = stop.target();
  out.stagnation_generations = static_cast<std::size_t>(stop.stagnation_generations());
  out.wall_seconds = stop.wall_seconds();
  return out;
}

proto::MigrationSettings ToProto(const MigrationParams& m) {
  proto::MigrationSettings out;
  out.set_interval(static_cast<std::uint32_t>(m.interval));
  out.set_migrants(static_cast<std::uint32_t>(m.migrants));
  out.set_topology(std::string(TopologyName(m.topology)));
  out.set_policy(std::string(MigrationPolicyName(m.policy)));
  return out;
}

MigrationParams FromProto(const proto::MigrationSettings& m) {
  MigrationParams out;
  out.interval = m.interval();
  out.migrants = m.migrants();
  out.topology = ParseTopology(m.topology());
  out.policy = ParseMigrationPolicy(m.policy());
  return out;
}

proto::IslandModelSettings ToProto(const IslandModelParams& p) {
  proto::IslandModelSettings out;
  out.set_islands(static_cast<std::uint32_t>(p.islands));
  *out.mutable_algorithm() = ToProto(p.algorithm);
  *out.mutable_migration() = ToProto(p.migration);
  out.set_asynchronous(p.asynchronous);
  out.set_threads(static_cast<std::uint32_t>(p.threads));
  return out;
}

IslandModelParams FromProto(const proto::IslandModelSettings& p) {
  IslandModelParams out;
  out.islands = p.islands();
  out.algorithm = FromProto(p.algorithm());
  out.migration = FromProto(p.migration());
  out.asynchronous = p.asynchronous();
  out.threads = p.threads();
  ValidateIslandModelParams(out);
  return out;
}

proto::IslandCheckpoint ToProto(const IslandCheckpoint& c) {
  proto::IslandCheckpoint out;
  out.set_protocol_version(kEngineProtocolVersion);
  *out.mutable_algorithm() = ToProto(c.algorithm);
  *out.mutable_stop() = ToProto(c.stop);
  *out.mutable_x() = ToProto(c.state.population.x);
  *out.mutable_f() = ToProto(c.state.population.f);
  for (const auto& [name, value] : c.state.memory) {
    auto* entry = out.add_memory();
    entry->set_name(name);
    *entry->mutable_value() = ToProto(value);
  }
  out.set_generation(c.state.generation);
  out.set_evaluations(c.state.evaluations);
  out.mutable_champion_x()->Add(c.state.champion_x.data(),
                                c.state.champion_x.data() + c.state.champion_x.size());
  out.mutable_champion_f()->Add(c.state.champion_f.data(),
                                c.state.champion_f.data() + c.state.champion_f.size());
  out.mutable_rng()->set_seed(c.rng.seed);
  for (const std::uint64_t w : c.rng.words) out.mutable_rng()->add_words(w);
  *out.mutable_progress() = ToProto(c.progress);
  if (c.stopped) out.set_stop_reason(std::string(StopReasonName(*c.stopped)));
  return out;
}

IslandCheckpoint FromProto(const proto::IslandCheckpoint& c) {
  CheckVersion(c.protocol_version(), "island checkpoint");
  IslandCheckpoint out;
  out.algorithm = FromProto(c.algorithm());
  out.stop = FromProto(c.stop());
  out.state.population.x = FromProto(c.x(), "x");
  out.state.population.f = FromProto(c.f(), "f");
  if (out.state.population.x.cols() != out.state.population.f.cols())
    throw Error("island checkpoint: population and fitness differ in size");
  for (const auto& entry : c.memory())
    out.state.memory[entry.name()] = FromProto(entry.value(), entry.name().c_str());
  out.state.generation = Count(c.generation(), "generation");
  out.state.evaluations = static_cast<std::size_t>(c.evaluations());
  out.state.champion_x = Vector(c.champion_x());
  out.state.champion_f = Vector(c.champion_f());
  if (c.rng().words_size() != 4) throw Error("island checkpoint: generator state needs 4 words");
  out.rng.seed = c.rng().seed();
  for (int i = 0; i < 4; ++i) out.rng.words[static_cast<std::size_t>(i)] = c.rng().words(i);
  if (out.rng.words == std::array<std::uint64_t, 4>{})
    throw Error("island checkpoint: an all-zero generator state never leaves zero");
  out.progress = FromProto(c.progress());
  out.stopped = ParseStopReason(c.stop_reason());
  // A trial restore catches shapes that do not fit the parameters before anyone relies on them.
  if (!IsUnstarted(out.state)) MakeAlgorithm(out.algorithm)->Restore(out.state);
  return out;
}

proto::ArchipelagoCheckpoint ToProto(const ArchipelagoCheckpoint& c) {
  proto::ArchipelagoCheckpoint out;
  out.set_protocol_version(kEngineProtocolVersion);
  *out.mutable_settings() = ToProto(c.params);
  *out.mutable_stop() = ToProto(c.stop);
  out.set_seed(c.seed);
  out.set_epoch(c.epoch);
  for (const IslandCheckpoint& island : c.islands) *out.add_islands() = ToProto(island);
  *out.mutable_progress() = ToProto(c.progress);
  return out;
}

ArchipelagoCheckpoint FromProto(const proto::ArchipelagoCheckpoint& c) {
  CheckVersion(c.protocol_version(), "archipelago checkpoint");
  ArchipelagoCheckpoint out;
  out.params = FromProto(c.settings());
  out.stop = FromProto(c.stop());
  out.seed = c.seed();
  out.epoch = Count(c.epoch(), "epoch");
  if (static_cast<std::size_t>(c.islands_size()) != out.params.islands) {
    throw Error("archipelago checkpoint holds " + std::to_string(c.islands_size()) +
                " islands, its settings say " + std::to_string(out.params.islands));
  }
  for (const auto& island : c.islands()) out.islands.push_back(FromProto(island));
  out.progress = FromProto(c.progress());
  return out;
}

}  // namespace evoslam
