// The service's scaling and overhead: one island localization job whose fitness costs over a
// millisecond (a full-circle heading search at 0.01 degrees), run four ways on this host:
//   library   - Localize() in this process, the islands on OpenMP threads, no messages at all;
//   embedded  - the default path of `evoslam localize`: coordinator and workers in this process,
//               inproc sockets;
//   cluster/N - an evoslam-coordinator process and N evoslam-worker processes of one thread
//               each, over TCP on localhost, the job submitted through the socket API.
// Parallel efficiency is cluster/1 / (2 x cluster/2); the ZeroMQ path's overhead is cluster/2
// against library with two threads. Each benchmark runs one warm-up job first (dataset upload,
// fetch and parsing), then times whole jobs.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/embedded_service.h"
#include "common/io/carmen_reader.h"
#include "common/localization/localize_params.h"
#include "common/localization/localizer.h"
#include "common/service/service_client.h"
#include "common/transform/angle_units.h"
#include "common/util/temp_dir.h"
#include "tests/process_testing.h"

namespace evoslam {
namespace {

constexpr int kPort = 18555;

// The simulated corridor on disk, and the job's settings.
class ServiceBenchJob {
 public:
  ServiceBenchJob() : dir_("evoslam-service-bench") {
    testing::ChildProcess simulate(
        {std::string(EVOSLAM_BINARY_DIR) + "/cli/evoslam", "simulate", "--world", "s-corridor",
         "--noise-uniform", "0.2", "--seed", "1", "--out", (dir_ / "sim").string()},
        dir_ / "simulate.log");
    if (simulate.Wait(std::chrono::seconds(60)) != 0) throw Error("evoslam simulate failed");
    options_.seed = 1;
    options_.max_scans = 4;
    EstimatorParams& e = options_.estimator;
    e.optimizer = ParseOptimizer("island", e.algorithm);
    e.algorithm.de.population = 8;
    e.generations = 10;
    e.islands = 4;
    e.migration.interval = 5;
    // A heading search over the full circle in 0.01 degree steps: over 1 ms per evaluation.
    e.heading_half_window = 3.14159265358979323846;
    e.heading_step = Radians(0.01);
  }

  std::filesystem::path map() const { return dir_ / "sim" / "world.lines"; }
  std::filesystem::path log() const { return dir_ / "sim" / "log.clf"; }
  const LocalizeOptions& options() const { return options_; }
  const std::filesystem::path& dir() const { return dir_.path(); }

  proto::JobSpec Spec(ServiceClient& client) const {
    proto::JobSpec spec;
    spec.set_kind(proto::JOB_KIND_LOCALIZE);
    *spec.mutable_localize() = ToProto(options_);
    *spec.mutable_log() = client.Upload(log());
    *spec.mutable_map() = client.Upload(map());
    return spec;
  }

 private:
  TempDir dir_;
  LocalizeOptions options_;
};

const ServiceBenchJob& Job() {
  static const ServiceBenchJob job;
  return job;
}

// Submits the job and waits for its result.
void RunJob(ServiceClient& client, const proto::JobSpec& spec) {
  const std::string id = client.Submit(spec);
  const proto::JobStatus s = client.Watch(id, {});
  if (s.state() != proto::JOB_STATE_SUCCEEDED) throw Error(id + " failed: " + s.error());
  benchmark::DoNotOptimize(client.Result(id));
}

void BM_IslandJobLibrary(benchmark::State& state) {
  const ServiceBenchJob& job = Job();
  const Dataset dataset = ReadCarmen(job.log());
  const MapModel map = LoadMapModel(job.map());
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(Localize(map, dataset, job.options()));
  omp_set_num_threads(omp_get_num_procs());
}
BENCHMARK(BM_IslandJobLibrary)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

void BM_IslandJobEmbedded(benchmark::State& state) {
  const ServiceBenchJob& job = Job();
  cli::EmbeddedService service(static_cast<std::size_t>(state.range(0)), 1);
  ServiceClient client(service.context(), service.client_options());
  const proto::JobSpec spec = job.Spec(client);
  RunJob(client, spec);  // warm-up: fetch and parse
  for (auto _ : state) RunJob(client, spec);
}
BENCHMARK(BM_IslandJobEmbedded)->Arg(2)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

void BM_IslandJobCluster(benchmark::State& state) {
  const ServiceBenchJob& job = Job();
  const std::string clients = "tcp://127.0.0.1:" + std::to_string(kPort);
  const std::string workers = "tcp://127.0.0.1:" + std::to_string(kPort + 1);
  const std::string bin = EVOSLAM_BINARY_DIR;
  const std::filesystem::path db = job.dir() / ("bench-" + std::to_string(state.range(0)) + ".db");
  std::filesystem::remove(db);
  testing::ChildProcess coordinator(
      {bin + "/coordinator/evoslam-coordinator", "--db", db.string(), "--clients", clients,
       "--workers", workers, "--log-level", "warn"},
      job.dir() / "coordinator.log");
  std::vector<std::unique_ptr<testing::ChildProcess>> pool;
  for (int i = 0; i < state.range(0); ++i) {
    pool.push_back(std::make_unique<testing::ChildProcess>(
        std::vector<std::string>{bin + "/worker/evoslam-worker", "--connect", workers, "--threads",
                                 "1", "--log-level", "warn"},
        job.dir() / ("worker" + std::to_string(i) + ".log")));
  }
  zmq::context_t context;
  ClientOptions options;
  options.endpoint = clients;
  ServiceClient client(context, options);
  while (client.Workers().size() < pool.size())
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const proto::JobSpec spec = job.Spec(client);
  RunJob(client, spec);  // warm-up: upload, fetch and parse
  for (auto _ : state) RunJob(client, spec);
}
BENCHMARK(BM_IslandJobCluster)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

// What one evaluation of the job's fitness costs, one thread.
void BM_IslandJobFitness(benchmark::State& state) {
  const ServiceBenchJob& job = Job();
  const Dataset dataset = ReadCarmen(job.log());
  const MapModel map = LoadMapModel(job.map());
  const ScanProblem problem =
      MakeScanProblem(map, dataset, 1, dataset.scans[0].pose, job.options());
  Eigen::MatrixXd x = 0.5 * (problem.problem->lower() + problem.problem->upper());
  double f = 0.0;
  omp_set_num_threads(1);
  for (auto _ : state) {
    problem.problem->Evaluate(x, std::span<double>(&f, 1));
    benchmark::DoNotOptimize(f);
  }
  omp_set_num_threads(omp_get_num_procs());
}
BENCHMARK(BM_IslandJobFitness)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace evoslam
