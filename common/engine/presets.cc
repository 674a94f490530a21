#include "common/engine/presets.h"

#include "common/util/error.h"

namespace evoslam {
namespace {

StopCriteria Generations(std::size_t generations) {
  StopCriteria stop;
  stop.max_generations = generations;
  return stop;
}

std::vector<Preset> MakePresets() {
  std::vector<Preset> presets;
  {
    Preset p{"de-000",
             "000 and 003: DE/rand/1/exp, 25 individuals, 25 generations, F 0.6, CR 0.9",
             {},
             Generations(25)};
    p.algorithm.kind = AlgorithmKind::kDe;
    presets.push_back(p);
  }
  {
    Preset p{"pso-003",
             "003: PSO with twice the DE population (50 particles), 25 generations; the "
             "coefficients are illegible in our copy, so Clerc's constriction values are used",
             {},
             Generations(25)};
    p.algorithm.kind = AlgorithmKind::kPso;
    p.algorithm.pso.particles = 50;
    presets.push_back(p);
  }
  for (const AlgorithmKind kind : {AlgorithmKind::kSga, AlgorithmKind::kAga}) {
    const bool sga = kind == AlgorithmKind::kSga;
    Preset p{sga ? "sga-003" : "aga-003",
             std::string(sga ? "003: SGA" : "003: aGA (Moravec 2012), two chromosomes each") +
                 ", 16 bits a coordinate on the 1 cm grid, two-point crossover of 5 pairs from "
                 "the better half, 2 elitist mutants, the 8 worst replaced; population (20) and "
                 "generations (50, about DE's budget) are illegible in our copy and ours",
             {},
             Generations(50)};
    p.algorithm.kind = kind;
    p.algorithm.ga.grid_step = 0.01;
    presets.push_back(p);
  }
  {
    Preset p{"pso-002-local",
             "002 local search: 10 particles, c1 = c2 = 2; w and the iteration count are not "
             "given, 0.7 and 20 are ours (with c = 2 the velocity clamp keeps the swarm bounded)",
             {},
             Generations(20)};
    p.algorithm.kind = AlgorithmKind::kPso;
    p.algorithm.pso.particles = 10;
    p.algorithm.pso.inertia = 0.7;
    p.algorithm.pso.c1 = 2.0;
    p.algorithm.pso.c2 = 2.0;
    presets.push_back(p);
  }
  {
    Preset p{"mu+lambda-002",
             "002 section 4, global search: mu 10, lambda 7 mu, q 5, Pm 0.05, Pc 0.8, 100 "
             "generations; columns of three (error, mean) pairs",
             {},
             Generations(100)};
    p.algorithm.kind = AlgorithmKind::kMuPlusLambda;
    presets.push_back(p);
  }
  {
    Preset p{"immune-004",
             "004 section 4: population 50, p_I 0.3, p_C 0.9, p_M 0.08; 300 generations (Table 1) "
             "or 20 generations without improvement (Table 2), whichever comes first",
             {},
             Generations(300)};
    p.algorithm.kind = AlgorithmKind::kImmune;
    p.stop.stagnation_generations = 20;
    presets.push_back(p);
  }
  {
    Preset p{"jde-brest2006",
             "Brest et al. 2006 (cited by 000): jDE/rand/1/bin, tau 0.1, F in [0.1, 1.0), "
             "population 100",
             {},
             Generations(1000)};
    p.algorithm.kind = AlgorithmKind::kJde;
    p.algorithm.jde.population = 100;
    presets.push_back(p);
  }
  return presets;
}

}  // namespace

std::span<const Preset> Presets() {
  static const std::vector<Preset> presets = MakePresets();
  return presets;
}

const Preset& FindPreset(std::string_view name) {
  for (const Preset& p : Presets()) {
    if (p.name == name) return p;
  }
  std::string valid;
  for (const Preset& p : Presets()) valid += (valid.empty() ? "" : ", ") + p.name;
  throw Error("unknown preset '" + std::string(name) + "' (expected one of: " + valid + ")");
}

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const Preset& p : Presets()) names.push_back(p.name);
  return names;
}

}  // namespace evoslam
