// Our evolutionary engine against pagmo 2: each of our algorithms and pagmo's counterpart, with the
// same settings, on the same problem with the same budget. Rows pair up by name,
// BM_Engine<problem>/<algorithm>/evoslam against BM_Engine<problem>/<algorithm>/pagmo;
// BM_EngineF3Batch measures what the pagmo adapter adds to an F3 evaluation.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "bench/corridor_scene.h"
#include "bench/engines.h"
#include "bench/serial_test_function.h"
#include "common/localization/scan_match_problem.h"
#include "common/localization/segment_renderer.h"
#include "common/transform/angle_units.h"

namespace evoslam {
namespace {

// Seeds per benchmark, one run each: enough for a median that one lucky run cannot move.
constexpr int kSeeds = 11;

double Median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

const Problem& Rastrigin30() {
  static const SerialTestFunction problem(TestFunction::kRastrigin, 30);
  return problem;
}

// Nearly free (30 multiply-adds), so that a run's time is the engine's own work.
const Problem& Sphere30() {
  static const SerialTestFunction problem(TestFunction::kSphere, 30);
  return problem;
}

// The estimator's F3 problem for scan 100 of the corridor, centred on scan 99's true pose as
// continual localization would centre it: a 60 cm window, 361 beams, +-30 degrees of heading in
// 0.5 degree steps.
const Problem& F3() {
  const LaserScan& scan = Corridor().log.scans[100];
  const Pose2 center = *Corridor().log.scans[99].true_pose;
  static const SegmentRenderer renderer(
      TemporaryMap(Corridor().world.map, center.translation(), 8.5));
  static const ShiftedScanProblem problem(renderer, FitnessParams{},
                                          MakeShiftLayout(scan, Radians(30.0), Radians(0.5)),
                                          PrepareObservation(scan, 8.0f), 8.0f, center, 0.6);
  return problem;
}

// One run per iteration, seed after seed, so every repetition replays the same kSeeds runs. One
// thread: pagmo's DE and PSO evaluate one candidate at a time, so threads would speed up only our
// side, and these rows compare the engines.
void RunEngine(benchmark::State& state, const Problem& problem, const Budget& budget,
               const Engine& engine) {
  omp_set_num_threads(1);
  std::vector<double> best;
  std::size_t evaluations = 0;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    const EngineRun run = engine(problem, budget, ++seed);
    best.push_back(run.best_fitness);
    evaluations += run.evaluations;
  }
  omp_set_num_threads(omp_get_num_procs());
  const auto total = static_cast<double>(evaluations);
  state.counters["evals/run"] = benchmark::Counter(total, benchmark::Counter::kAvgIterations);
  state.counters["evals/s"] = benchmark::Counter(total, benchmark::Counter::kIsRate);
  state.counters["time/eval"] =
      benchmark::Counter(total, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["best_median"] = Median(best);
  state.counters["best_min"] = *std::min_element(best.begin(), best.end());
  state.counters["best_max"] = *std::max_element(best.begin(), best.end());
}

void RegisterEngine(const std::string& name, const Problem& (*problem)(), Budget budget,
                    Engine engine) {
  benchmark::RegisterBenchmark(name.c_str(),
                               [problem, budget, engine](benchmark::State& state) {
                                 RunEngine(state, problem(), budget, engine);
                               })
      ->Iterations(kSeeds)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
}

// Registers <family>/<algorithm>/evoslam and <family>/<algorithm>/pagmo.
void RegisterContest(const std::string& family, const Problem& (*problem)(), Budget budget,
                     const std::string& algorithm, Engine evoslam, Engine pagmo) {
  RegisterEngine(family + "/" + algorithm + "/evoslam", problem, budget, std::move(evoslam));
  RegisterEngine(family + "/" + algorithm + "/pagmo", problem, budget, std::move(pagmo));
}

// The same 25 F3 candidates evaluated in batches of Arg candidates, on one thread. pagmo evaluates
// batches of one, each paying for a parallel region and the problem's scratch buffers, which ours
// pays once per generation: the difference is a cost of the adapter, not of pagmo.
void BM_EngineF3Batch(benchmark::State& state) {
  const Problem& problem = F3();
  const Eigen::Index batch = state.range(0);
  constexpr Eigen::Index kCandidates = 25;
  Rng rng(3);
  Eigen::MatrixXd x(2, kCandidates);
  for (Eigen::Index i = 0; i < kCandidates; ++i) {
    for (Eigen::Index j = 0; j < 2; ++j)
      x(j, i) = rng.Uniform(problem.lower()(j), problem.upper()(j));
  }
  std::vector<double> fitness(kCandidates);
  omp_set_num_threads(1);
  for (auto _ : state) {
    for (Eigen::Index i = 0; i < kCandidates; i += batch) {
      problem.Evaluate(
          x.middleCols(i, batch),
          std::span(fitness).subspan(static_cast<std::size_t>(i), static_cast<std::size_t>(batch)));
    }
    benchmark::DoNotOptimize(fitness.data());
  }
  omp_set_num_threads(omp_get_num_procs());
  state.counters["time/eval"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kCandidates),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_EngineF3Batch)->ArgName("batch")->Arg(1)->Arg(25)->UseRealTime();

// The comparisons. An algorithm joins them with one RegisterContest line per problem.
const bool kRegistered = [] {
  // Rastrigin is separable and multimodal; rand/1/bin with Storn's F 0.5, CR 0.9 is the common
  // textbook setting for it. 50 individuals for 1000 generations: 50,050 evaluations.
  const Budget rastrigin{50, 1000};
  const DeParams rastrigin_de{.strategy = DeStrategy::kRand1Bin, .f = 0.5, .cr = 0.9};
  RegisterContest("BM_EngineRastrigin30", Rastrigin30, rastrigin, "de", EvoslamDe(rastrigin_de),
                  PagmoDe(rastrigin_de));
  RegisterContest("BM_EngineRastrigin30", Rastrigin30, rastrigin, "pso", EvoslamPso(PsoParams{}),
                  PagmoPso(PsoParams{}));

  // The papers' localization settings: POP 25, GEN 25, DE/rand/1/exp with F 0.6, CR 0.9.
  const Budget f3{25, 25};
  RegisterContest("BM_EngineF3", F3, f3, "de", EvoslamDe(DeParams{}), PagmoDe(DeParams{}));
  RegisterContest("BM_EngineF3", F3, f3, "pso", EvoslamPso(PsoParams{}), PagmoPso(PsoParams{}));

  // 003's SGA: binary chromosomes (16 bits a coordinate), 20 individuals, 5 pairs and 2 elitist
  // mutants a generation, against pagmo's real-coded SGA with the budget's population.
  GaParams sga;
  RegisterContest("BM_EngineRastrigin30", Rastrigin30, rastrigin, "sga", EvoslamSga(sga),
                  PagmoSga());
  // The same with about one flipped bit per child (480 bits), which 003 does not have.
  GaParams sga_flip = sga;
  sga_flip.bit_flip = 1.0 / 480;
  RegisterEngine("BM_EngineRastrigin30/sga-bitflip/evoslam", Rastrigin30, rastrigin,
                 EvoslamSga(sga_flip));
  GaParams sga_grid = sga;
  sga_grid.grid_step = 0.01;  // the papers' 1 cm search grid
  RegisterContest("BM_EngineF3", F3, f3, "sga", EvoslamSga(sga_grid), PagmoSga());

  // Island models of DE, 4 islands on 2 threads, ring, 1 migrant every 10 generations (5 on
  // F3's 25 generations); pagmo's thread islands each run on a thread of their own.
  const Budget rastrigin_islands{100, 500};
  RegisterContest("BM_EngineRastrigin30", Rastrigin30, rastrigin_islands, "islands-de",
                  EvoslamIslands(rastrigin_de, IslandBudget{}), PagmoIslands(rastrigin_de, {}));
  RegisterEngine("BM_EngineRastrigin30/islands-de-async/evoslam", Rastrigin30, rastrigin_islands,
                 EvoslamIslands(rastrigin_de, IslandBudget{.asynchronous = true}));
  RegisterEngine("BM_EngineRastrigin30/islands-de-lockstep/pagmo", Rastrigin30, rastrigin_islands,
                 PagmoIslands(rastrigin_de, IslandBudget{.lockstep = true}));
  const Budget f3_islands{100, 25};
  const IslandBudget f3_ring{.interval = 5};
  RegisterContest("BM_EngineF3", F3, f3_islands, "islands-de", EvoslamIslands(DeParams{}, f3_ring),
                  PagmoIslands(DeParams{}, f3_ring));

  // What each engine costs per evaluation beyond the fitness itself.
  const Budget overhead{50, 1000};
  RegisterContest("BM_EngineOverhead", Sphere30, overhead, "de", EvoslamDe(DeParams{}),
                  PagmoDe(DeParams{}));
  RegisterContest("BM_EngineOverhead", Sphere30, overhead, "pso", EvoslamPso(PsoParams{}),
                  PagmoPso(PsoParams{}));
  RegisterContest("BM_EngineOverhead", Sphere30, overhead, "sga", EvoslamSga(sga), PagmoSga());
  RegisterContest("BM_EngineOverhead", Sphere30, Budget{100, 500}, "islands-de",
                  EvoslamIslands(DeParams{}, IslandBudget{}), PagmoIslands(DeParams{}, {}));
  RegisterEngine("BM_EngineOverhead/islands-de-async/evoslam", Sphere30, Budget{100, 500},
                 EvoslamIslands(DeParams{}, IslandBudget{.asynchronous = true}));
  return true;
}();

}  // namespace
}  // namespace evoslam
