// The service's acceptance tests: real evoslam-coordinator, evoslam-worker and evoslam
// processes on the loopback interface, driven the way an operator would drive them, with faults
// injected (kill -9, SIGSTOP, SIGTERM, garbage frames, refused keys). A job's result must not
// depend on where it ran or on what went wrong meanwhile: every finished job is compared with
// the embedded run (`evoslam localize` without --coordinator) of the same command line.
#include <gtest/gtest.h>
#include <zmq.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/io/carmen_reader.h"
#include "common/io/carmen_writer.h"
#include "common/io/relations.h"
#include "common/localization/localize_params.h"
#include "common/protocol/wire.h"
#include "common/protocol/zmq_io.h"
#include "common/report/slam_outputs.h"
#include "common/service/service_client.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/rss_slam.h"
#include "common/slam/slam_params.h"
#include "common/util/scratch_dir.h"
#include "common/util/sha256.h"
#include "common/util/temp_dir.h"
#include "tests/process_testing.h"

namespace {

namespace fs = std::filesystem;
namespace proto = evoslam::proto;
using evoslam::testing::ChildProcess;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

// How long a job of these tests may take at most, on a loaded 2-core machine.
constexpr auto kJobTimeout = 60s;

// deploy/test.sh runs these tests again on a Debug build under AddressSanitizer, where a
// localization runs some 40 times slower: there the jobs have a tenth of the scans (and the
// load test a tenth of the jobs), to take about as long as here.
#ifdef EVOSLAM_SANITIZED
constexpr std::size_t kScaleDown = 10;
#else
constexpr std::size_t kScaleDown = 1;
#endif

// `n` scans, or fewer under the sanitizers; never under 3, so that a job still has a middle.
constexpr std::size_t Scans(std::size_t n) { return std::max<std::size_t>(3, n / kScaleDown); }

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Polls `done` until it holds or `timeout` passes; returns whether it held.
template <typename Predicate>
bool WaitUntil(Predicate done, Clock::duration timeout, Clock::duration every = 20ms) {
  const Clock::time_point until = Clock::now() + timeout;
  for (;;) {
    if (done()) return true;
    if (Clock::now() >= until) return false;
    std::this_thread::sleep_for(every);
  }
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::span<const std::byte> AsBytes(const std::string& frame) {
  return {reinterpret_cast<const std::byte*>(frame.data()), frame.size()};
}

bool Finished(const proto::JobStatus& s) {
  return s.state() == proto::JOB_STATE_SUCCEEDED || s.state() == proto::JOB_STATE_FAILED ||
         s.state() == proto::JOB_STATE_CANCELLED;
}

std::string Describe(const proto::JobStatus& s) {
  return s.job_id() + " state " + std::to_string(s.state()) + " " + s.phase() + " " +
         std::to_string(s.done()) + "/" + std::to_string(s.total()) +
         (s.error().empty() ? "" : " error: " + s.error());
}

// report.json without what depends on the machine and the moment: timings and thread counts
// (a SLAM report's phase times and global search seconds among them).
std::string StableReport(const fs::path& path) {
  std::istringstream in(ReadAll(path));
  std::string line, out;
  while (std::getline(in, line)) {
    const std::string key = line.substr(std::min(line.size(), line.find_first_not_of(' ')));
    bool timing = false;
    for (const char* k : {"runtime_s", "scans_per_second", "threads", "seconds", "local_s",
                          "detection_s", "global_s", "total_s"}) {
      timing |= key.starts_with("\"" + std::string(k) + "\":");
    }
    if (timing) continue;
    out += line + '\n';
  }
  return out;
}

// A localization job as the command line states it.
struct Job {
  std::size_t scans = 40;
  std::string optimizer = "island";
  std::size_t islands = 2;
  std::size_t gen = 25;
  std::size_t pop = 25;
  std::uint64_t seed = 1;

  std::string Key() const {
    return optimizer + "-s" + std::to_string(scans) + "-i" + std::to_string(islands) + "-g" +
           std::to_string(gen) + "-p" + std::to_string(pop) + "-seed" + std::to_string(seed);
  }
};

// Long enough (many epochs of several islands) that a test can disturb it while it runs: a few
// seconds on two single-threaded workers.
const Job kLongJob{.scans = Scans(60), .optimizer = "island", .islands = 4, .gen = 50};

// The job the command line `LocalizeArgs(job, ...)` describes, built as cli/localize_command.cc
// builds it, on datasets already uploaded.
proto::JobSpec SpecFor(const Job& job, const proto::DatasetRef& log, const proto::DatasetRef& map,
                       const fs::path& log_path, const fs::path& map_path) {
  evoslam::LocalizeOptions options;
  evoslam::EstimatorParams& e = options.estimator;
  e.optimizer = evoslam::ParseOptimizer(job.optimizer, e.algorithm);
  e.algorithm.de.population = e.algorithm.jde.population = e.algorithm.pso.particles =
      e.algorithm.ga.population = job.pop;
  e.algorithm.mu_plus_lambda.mu = job.pop;
  e.algorithm.mu_plus_lambda.lambda = 7 * job.pop;
  e.algorithm.immune.population = job.pop;
  e.algorithm.immune.recombinations = job.pop - job.pop / 5;
  e.algorithm.immune.mutations = job.pop / 5;
  e.generations = job.gen;
  e.islands = job.islands;
  e.migration.interval = 5;
  // In degrees times the same constant as the command line, so that the radians have the same
  // bits.
  constexpr double kDeg = std::numbers::pi / 180.0;
  e.heading_half_window = 30.0 * kDeg;
  e.heading_step = 0.5 * kDeg;
  options.seed = job.seed;
  options.max_scans = job.scans;
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_LOCALIZE);
  proto::LocalizeParams& p = *spec.mutable_localize();
  p = evoslam::ToProto(options);
  p.set_map(map_path.string());
  p.set_log(log_path.string());
  p.set_grid_resolution_m(0.05);
  *spec.mutable_log() = log;
  *spec.mutable_map() = map;
  return spec;
}

// A bare DEALER socket that sends whatever frames a test makes, as a buggy or hostile peer would.
class RawDealer {
 public:
  RawDealer(zmq::context_t& context, const std::string& endpoint)
      : socket_(context, zmq::socket_type::dealer) {
    socket_.set(zmq::sockopt::linger, 0);
    socket_.connect(endpoint);
  }

  void Send(const std::vector<std::string>& frames) {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      socket_.send(zmq::buffer(frames[i]),
                   i + 1 < frames.size() ? zmq::send_flags::sndmore : zmq::send_flags::none);
    }
  }

  // The next message's frames; nullopt when none comes within `timeout`.
  std::optional<std::vector<std::string>> Receive(std::chrono::milliseconds timeout) {
    std::vector<zmq::pollitem_t> items = {{socket_.handle(), 0, ZMQ_POLLIN, 0}};
    zmq::poll(items, timeout);
    auto frames = evoslam::ReceiveFrames(socket_);
    if (!frames) return std::nullopt;
    std::vector<std::string> texts;
    for (const zmq::message_t& f : *frames) texts.push_back(evoslam::Text(f));
    return texts;
  }

 private:
  zmq::socket_t socket_;
};

// A running coordinator and the endpoints it bound.
struct CoordinatorProcess {
  ChildProcess* process = nullptr;  // owned by the fixture, which kills it at the end
  std::string clients, workers;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
  double seconds = 0;
};

class ServiceTest : public ::testing::Test {
 protected:
  // One small simulated world for the whole binary (ctest runs each test in a process of its
  // own, so there it is made once per test; it takes a few milliseconds).
  static void SetUpTestSuite() {
    world_ = new evoslam::TempDir("evoslam-service-world");
    ChildProcess sim({EVOSLAM_CLI, "simulate", "--world", "s-corridor", "--noise-uniform", "0.2",
                      "--seed", "1", "--out", world_->path().string()},
                     world_->path() / "simulate.log");
    const auto status = sim.Wait(60s);
    ASSERT_TRUE(status && WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << sim.Log();
  }
  static void TearDownTestSuite() {
    delete world_;
    world_ = nullptr;
  }
  static fs::path Map() { return world_->path() / "world.lines"; }
  static fs::path Log() { return world_->path() / "log.clf"; }

  void TearDown() override {
    if (!HasFailure()) return;
    // What the processes said is what explains a failure; the scratch folder goes with the test.
    for (const auto& p : processes_) {
      std::cerr << "----- " << p->log_path().filename().string() << " -----\n";
      const std::string log = p->Log();
      std::cerr << (log.size() > 20000 ? "..." + log.substr(log.size() - 20000) : log) << "\n";
    }
  }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  ChildProcess& Start(const std::vector<std::string>& argv, const std::string& log_name) {
    // Their temporary folders (a coordinator's datasets, a worker's cache) go in the scratch
    // folder, so that even a process killed with -9 leaves nothing behind.
    processes_.push_back(std::make_unique<ChildProcess>(
        argv, dir_ / log_name,
        std::vector<std::string>{"TMPDIR=" + dir_.path().string(), "OMP_WAIT_POLICY=PASSIVE"}));
    return *processes_.back();
  }

  // Starts a coordinator with short heartbeats, checkpoints at every epoch, and ports the system
  // picks (unless given: a restart binds the same ones), and waits until it listens.
  CoordinatorProcess StartCoordinator(const std::string& name,
                                      const std::vector<std::string>& extra = {},
                                      const std::string& clients = "tcp://127.0.0.1:*",
                                      const std::string& workers = "tcp://127.0.0.1:*") {
    std::vector<std::string> argv = {EVOSLAM_COORDINATOR,
                                     "--db",
                                     Path("jobs.db"),
                                     "--clients",
                                     clients,
                                     "--workers",
                                     workers,
                                     "--heartbeat",
                                     "0.2",
                                     "--liveness",
                                     "3",
                                     "--checkpoint-interval",
                                     "0",
                                     "--log-level",
                                     "info"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    ChildProcess& process = Start(argv, name + ".log");
    static const std::regex kListening(R"(clients on (\S+), workers on ([^\s,]+))");
    std::smatch match;
    std::string log;
    const bool listening = WaitUntil(
        [&] {
          log = process.Log();
          return std::regex_search(log, match, kListening) || !process.Alive();
        },
        20s);
    if (!listening || match.empty()) {
      throw std::runtime_error("the coordinator did not start listening:\n" + log);
    }
    return {&process, match[1], match[2]};
  }

  ChildProcess& StartWorker(const std::string& name, const std::string& endpoint,
                            const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv = {
        EVOSLAM_WORKER, "--connect", endpoint, "--heartbeat", "0.2", "--max-backoff",
        "0.5",          "--threads", "1",      "--log-level", "info"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return Start(argv, name + ".log");
  }

  // Runs the command line to its end.
  CommandResult Cli(const std::vector<std::string>& args, Clock::duration timeout = kJobTimeout) {
    std::vector<std::string> argv = {EVOSLAM_CLI};
    argv.insert(argv.end(), args.begin(), args.end());
    const Clock::time_point start = Clock::now();
    ChildProcess& process = Start(argv, "cli-" + std::to_string(++cli_runs_) + ".log");
    const auto status = process.Wait(timeout);
    CommandResult r;
    r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    r.output = process.Log();
    if (!status) {
      throw std::runtime_error("evoslam " + args.front() + " still runs after the timeout:\n" +
                               r.output);
    }
    r.exit_code = WIFEXITED(*status) ? WEXITSTATUS(*status) : -1;
    return r;
  }

  static std::vector<std::string> LocalizeArgs(const Job& job, const std::string& out) {
    std::vector<std::string> args = {"localize",
                                     "--map",
                                     Map().string(),
                                     "--log",
                                     Log().string(),
                                     "--max-scans",
                                     std::to_string(job.scans),
                                     "--optimizer",
                                     job.optimizer,
                                     "--gen",
                                     std::to_string(job.gen),
                                     "--pop",
                                     std::to_string(job.pop),
                                     "--seed",
                                     std::to_string(job.seed)};
    if (job.optimizer == "island") {
      for (const std::string& a : {std::string("--islands"), std::to_string(job.islands),
                                   std::string("--migration-interval"), std::string("5")})
        args.push_back(a);
    }
    if (!out.empty()) {
      args.push_back("--out");
      args.push_back(out);
    }
    return args;
  }

  // The job's outputs as the embedded run writes them: what every run of it must write.
  fs::path Reference(const Job& job) {
    const fs::path out = dir_ / ("reference-" + job.Key());
    if (!fs::exists(out / "trajectory.txt")) {
      const CommandResult r = Cli(LocalizeArgs(job, out.string()));
      if (r.exit_code != 0) throw std::runtime_error("the embedded run failed:\n" + r.output);
    }
    return out;
  }

  // The command line that runs the job on the coordinator at `clients`.
  static std::vector<std::string> RemoteArgs(const Job& job, const std::string& out,
                                             const std::string& clients,
                                             const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = LocalizeArgs(job, out);
    for (const std::string& a :
         {std::string("--coordinator"), clients, std::string("--timeout"), std::string("10")})
      args.push_back(a);
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  // Submits the job with `evoslam localize --detach` and returns its id.
  std::string SubmitDetached(const Job& job, const std::string& clients) {
    const CommandResult r = Cli(RemoteArgs(job, "", clients, {"--detach"}));
    static const std::regex kJobId(R"((^|\n)(job-\d+)\n)");
    std::smatch match;
    if (r.exit_code != 0 || !std::regex_search(r.output, match, kJobId)) {
      throw std::runtime_error("submitting failed:\n" + r.output);
    }
    return match[2];
  }

  evoslam::ServiceClient Client(const std::string& endpoint, double timeout_seconds = 10) {
    evoslam::ClientOptions options;
    options.endpoint = endpoint;
    options.timeout_seconds = timeout_seconds;
    return evoslam::ServiceClient(context_, options);
  }

  void WaitForWorkers(evoslam::ServiceClient& client, std::size_t n) {
    if (!WaitUntil([&] { return client.Workers().size() == n; }, 20s)) {
      throw std::runtime_error("the coordinator does not list " + std::to_string(n) +
                               " workers but " + std::to_string(client.Workers().size()));
    }
  }

  // Waits until the job has done at least `scans` scans of its `phase` ("local search" for a
  // SLAM job) but not all of them, and returns its status then. Throws when it finishes first:
  // the test could not disturb it mid-way.
  proto::JobStatus WaitForProgress(evoslam::ServiceClient& client, const std::string& job_id,
                                   std::uint64_t scans = 1, const std::string& phase = "localize") {
    proto::JobStatus s;
    const bool started = WaitUntil(
        [&] {
          s = client.Status(job_id);
          return Finished(s) || (s.phase() == phase && s.done() >= scans);
        },
        kJobTimeout, 10ms);
    if (!started || Finished(s) || s.done() >= s.total()) {
      throw std::runtime_error("the job did not stop mid-way to be disturbed: " + Describe(s));
    }
    return s;
  }

  proto::JobStatus WaitForEnd(evoslam::ServiceClient& client, const std::string& job_id) {
    proto::JobStatus s;
    if (!WaitUntil(
            [&] {
              s = client.Status(job_id);
              return Finished(s);
            },
            kJobTimeout, 50ms)) {
      throw std::runtime_error("the job did not finish in time: " + Describe(s));
    }
    return s;
  }

  // Kills the coordinator with SIGKILL mid-job, restarts it on the same database and endpoints
  // (the workers find it again by themselves) and follows the job to its end: it must resume
  // from its checkpoint and succeed, its progress in `before`'s phase never going back towards
  // the start. Returns the restarted coordinator.
  CoordinatorProcess KillAndResume(const CoordinatorProcess& c, const std::string& job_id,
                                   const proto::JobStatus& before) {
    if (!c.process->Kill(SIGKILL) || !c.process->Wait(5s)) {
      throw std::runtime_error("the coordinator could not be killed");
    }
    const CoordinatorProcess restarted =
        StartCoordinator("coordinator-restarted", {}, c.clients, c.workers);
    auto client = Client(restarted.clients);
    std::vector<proto::JobStatus> seen;
    proto::JobStatus end;
    EXPECT_TRUE(WaitUntil(
        [&] {
          end = client.Status(job_id);
          seen.push_back(end);
          return Finished(end);
        },
        kJobTimeout, 10ms))
        << Describe(end);
    EXPECT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
    EXPECT_NE(restarted.process->Log().find(job_id + ": resuming from its checkpoint"),
              std::string::npos);
    for (const proto::JobStatus& s : seen) {
      if (s.phase() == before.phase()) {
        EXPECT_GE(s.done(), before.done()) << Describe(s);
      }
    }
    return restarted;
  }

  // Writes a finished job's files into `out`, as `evoslam result` does.
  void FetchResult(evoslam::ServiceClient& client, const std::string& job_id, const fs::path& out) {
    fs::create_directories(out);
    for (const proto::ResultFile& f : client.Result(job_id)) {
      std::ofstream(out / f.name(), std::ios::binary) << f.content();
    }
  }

  // Waits for the job to end and checks it succeeded with the reference's trajectory.
  void ExpectSucceedsLike(evoslam::ServiceClient& client, const std::string& job_id,
                          const fs::path& reference) {
    const proto::JobStatus end = WaitForEnd(client, job_id);
    ASSERT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
    FetchResult(client, job_id, Path("result"));
    ExpectSameTrajectory(reference, Path("result"));
  }

  // A raw DEALER on the worker socket that has said Ready: a worker the test plays itself.
  std::unique_ptr<RawDealer> FakeWorker(const std::string& endpoint) {
    auto fake = std::make_unique<RawDealer>(context_, endpoint);
    proto::WorkerMessage ready;
    ready.mutable_ready()->set_hostname("fake");
    ready.mutable_ready()->set_threads(1);
    fake->Send({evoslam::Encode(ready)});
    return fake;
  }

  // The first task the coordinator sends `fake` within 10 s.
  static std::optional<proto::Task> AwaitTask(RawDealer& fake) {
    std::optional<proto::Task> task;
    WaitUntil(
        [&] {
          while (auto frames = fake.Receive(10ms)) {
            const auto m = evoslam::DecodeCoordinatorMessage(AsBytes(frames->front()));
            if (m.has_task()) task = m.task();
          }
          return task.has_value();
        },
        10s);
    return task;
  }

  static void ExpectSameTrajectory(const fs::path& expected, const fs::path& actual) {
    for (const char* name : {"trajectory.txt", "trajectory.tum"}) {
      ASSERT_TRUE(fs::exists(actual / name)) << actual / name;
      const std::string want = ReadAll(expected / name);
      ASSERT_FALSE(want.empty()) << expected / name;
      EXPECT_EQ(want, ReadAll(actual / name)) << name;
    }
  }

  static void ExpectSameOutputs(const fs::path& expected, const fs::path& actual) {
    ExpectSameTrajectory(expected, actual);
    for (const char* name : {"map.png", "report.json"}) {
      ASSERT_TRUE(fs::exists(expected / name)) << expected / name;
      ASSERT_TRUE(fs::exists(actual / name)) << actual / name;
    }
    // Compared as booleans: a binary file's bytes in a failure message help nobody.
    EXPECT_TRUE(ReadAll(expected / "map.png") == ReadAll(actual / "map.png")) << "map.png differs";
    EXPECT_EQ(StableReport(expected / "report.json"), StableReport(actual / "report.json"));
  }

  static evoslam::TempDir* world_;
  zmq::context_t context_;
  evoslam::testing::ScratchDir dir_;
  // Destroyed before dir_ (members go in reverse order): every process is killed before its
  // folder is removed.
  std::vector<std::unique_ptr<ChildProcess>> processes_;
  int cli_runs_ = 0;
};

evoslam::TempDir* ServiceTest::world_ = nullptr;

// ---- The same result wherever it runs ----

TEST_F(ServiceTest, AnIslandJobOnTwoWorkerProcessesWritesWhatTheEmbeddedRunWrites) {
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const Job job{.scans = Scans(40), .optimizer = "island", .islands = 3};
  const CommandResult r = Cli(RemoteArgs(job, Path("remote"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameOutputs(Reference(job), Path("remote"));
  // Both processes took part: the job really ran on them, not somewhere else.
  const auto workers = client.Workers();
  ASSERT_EQ(workers.size(), 2u);
  for (const proto::WorkerInfo& w : workers) EXPECT_GT(w.tasks_done(), 0u) << w.worker_id();
  EXPECT_TRUE(c.process->Alive());
}

TEST_F(ServiceTest, ASingleAlgorithmJobOnTwoWorkerProcessesWritesWhatTheEmbeddedRunWrites) {
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const Job job{.scans = Scans(30), .optimizer = "de"};
  const CommandResult r = Cli(RemoteArgs(job, Path("remote"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameOutputs(Reference(job), Path("remote"));
  // One task at a time goes to the worker idle the longest: both take turns.
  for (const proto::WorkerInfo& w : client.Workers())
    EXPECT_GT(w.tasks_done(), 0u) << w.worker_id();
}

// ---- Faults ----

TEST_F(ServiceTest, AJobOutlivesAWorkerKilledMidJob) {
  const fs::path reference = Reference(kLongJob);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  ChildProcess& victim = StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const std::string job_id = SubmitDetached(kLongJob, c.clients);
  const proto::JobStatus before = WaitForProgress(client, job_id);
  ASSERT_TRUE(victim.Kill(SIGKILL));
  ASSERT_TRUE(victim.Wait(5s));
  const proto::JobStatus end = WaitForEnd(client, job_id);
  ASSERT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
  EXPECT_EQ(end.done(), end.total());
  EXPECT_LT(before.done(), end.total());
  FetchResult(client, job_id, Path("result"));
  ExpectSameTrajectory(reference, Path("result"));
  EXPECT_TRUE(WaitUntil([&] { return client.Workers().size() == 1; }, 5s));
  EXPECT_TRUE(c.process->Alive());
}

TEST_F(ServiceTest, AJobResumesFromItsCheckpointAfterTheCoordinatorIsKilledAndRestarted) {
  const fs::path reference = Reference(kLongJob);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  std::string earlier_id, job_id;
  proto::JobStatus before;
  {
    auto client = Client(c.clients);
    WaitForWorkers(client, 2);
    earlier_id = SubmitDetached(Job{.scans = Scans(20)}, c.clients);
    ASSERT_EQ(WaitForEnd(client, earlier_id).state(), proto::JOB_STATE_SUCCEEDED);
    FetchResult(client, earlier_id, Path("earlier"));

    job_id = SubmitDetached(kLongJob, c.clients);
    // Several scans in, so that a job started again from nothing would be seen going back.
    before = WaitForProgress(client, job_id, std::max<std::size_t>(1, kLongJob.scans / 12));
  }
  // A client following the job: it asks again when the events stop.
  ChildProcess& watch = Start(
      {EVOSLAM_CLI, "watch", job_id, "--coordinator", c.clients, "--timeout", "2"}, "watch.log");
  const CoordinatorProcess restarted = KillAndResume(c, job_id, before);
  ASSERT_FALSE(HasFailure());
  auto client = Client(restarted.clients);
  FetchResult(client, job_id, Path("result"));
  ExpectSameTrajectory(reference, Path("result"));
  const auto watched = watch.Wait(10s);
  ASSERT_TRUE(watched) << "the watch did not see the job end";
  EXPECT_TRUE(WIFEXITED(*watched) && WEXITSTATUS(*watched) == 0) << watch.Log();
  EXPECT_NE(watch.Log().find(job_id + "  succeeded"), std::string::npos) << watch.Log();

  // What finished before the crash is still there, byte for byte.
  const CommandResult again = Cli({"result", earlier_id, "--out", Path("earlier-again"),
                                   "--coordinator", restarted.clients, "--timeout", "10"});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  std::size_t files = 0;
  for (const auto& f : fs::directory_iterator(dir_ / "earlier")) {
    ++files;
    EXPECT_TRUE(ReadAll(f.path()) == ReadAll(dir_ / "earlier-again" / f.path().filename()))
        << f.path().filename() << " differs after the restart";
  }
  EXPECT_GE(files, 5u);
}

TEST_F(ServiceTest, AStoppedWorkersTaskGoesToAnotherAndTheWorkerRejoinsWhenContinued) {
  const fs::path reference = Reference(kLongJob);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  ChildProcess& paused = StartWorker("worker1", c.workers);
  ChildProcess& other = StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const std::string job_id = SubmitDetached(kLongJob, c.clients);
  WaitForProgress(client, job_id);
  ASSERT_TRUE(paused.Kill(SIGSTOP));
  // The stopped worker holds a task: the one it had, or the next one the coordinator hands it
  // before it notices the silence (the islands keep both workers busy). After `liveness` missed
  // heartbeats the task goes to the other worker.
  static const std::regex kLost(
      R"(worker (\w+) is lost \(silent or overdue\); its task (t-\d+) goes to another)");
  std::smatch lost;
  std::string log;
  ASSERT_TRUE(WaitUntil(
      [&] {
        log = c.process->Log();
        return std::regex_search(log, lost, kLost);
      },
      10s));
  const std::string task = lost[2];
  ExpectSucceedsLike(client, job_id, reference);
  EXPECT_EQ(client.Workers().size(), 1u);

  ASSERT_TRUE(paused.Kill(SIGCONT));
  // It says Ready again and is listed again.
  CommandResult listed;
  EXPECT_TRUE(WaitUntil(
      [&] {
        listed = Cli({"workers", "--coordinator", c.clients, "--timeout", "10"});
        return listed.exit_code == 0 && Count(listed.output, " threads ") == 2;
      },
      10s, 100ms))
      << listed.output;
  // Its answer to the task it held is never taken. Either the coordinator drops it (it no longer
  // knows the worker), or the worker, told by the coordinator that its task went elsewhere,
  // throws it away itself; which of the two comes first is a race between the worker's threads.
  const std::string coordinator_log = c.process->Log();
  const bool dropped =
      coordinator_log.find("dropped a late answer for " + task) != std::string::npos ||
      coordinator_log.find("dropped an answer for " + task) != std::string::npos;
  const bool told = paused.Log().find("the coordinator asks for a new start") != std::string::npos;
  EXPECT_TRUE(dropped || told) << "the late answer to " << task << " went unnoticed";

  // The worker that came back does work: alone, it runs the next job.
  ASSERT_TRUE(other.Kill(SIGTERM));
  ASSERT_TRUE(other.Wait(10s));
  WaitForWorkers(client, 1);
  const Job small{.scans = Scans(10)};
  const CommandResult r = Cli(RemoteArgs(small, Path("after"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(small), Path("after"));
}

// A worker paused past its deadline and resumed while the job still runs comes back with a
// stale task in hand and a stale view of the coordinator; none of it may change the job.
TEST_F(ServiceTest, AWorkerPausedAndResumedMidJobDoesNotChangeItsResult) {
  Job job = kLongJob;
  job.scans = Scans(90);
  const fs::path reference = Reference(job);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  ChildProcess& paused = StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const std::string job_id = SubmitDetached(job, c.clients);
  WaitForProgress(client, job_id);
  std::size_t rounds = 0;
  for (; rounds < 3 && !Finished(client.Status(job_id)); ++rounds) {
    ASSERT_TRUE(paused.Kill(SIGSTOP));
    ASSERT_TRUE(WaitUntil(
        [&] { return Count(c.process->Log(), "is lost (silent or overdue)") > rounds; }, 10s));
    ASSERT_TRUE(paused.Kill(SIGCONT));
    ASSERT_TRUE(WaitUntil([&] { return client.Workers().size() == 2; }, 10s));
  }
  EXPECT_GE(rounds, 2u) << "the job ended too soon to be disturbed";
  ExpectSucceedsLike(client, job_id, reference);
}

TEST_F(ServiceTest, AWorkerStoppedWithSigtermFinishesItsTaskAndLeavesCleanly) {
  const fs::path reference = Reference(kLongJob);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  ChildProcess& leaving = StartWorker("worker1", c.workers, {"--grace", "2"});
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const std::string job_id = SubmitDetached(kLongJob, c.clients);
  WaitForProgress(client, job_id);
  ASSERT_TRUE(leaving.Kill(SIGTERM));
  const auto status = leaving.Wait(2s + 3s);  // its grace, and a margin for a loaded machine
  ASSERT_TRUE(status) << "still running after its grace";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << ChildProcess::Describe(*status);
  EXPECT_NE(leaving.Log().find("worker: left"), std::string::npos);
  EXPECT_EQ(leaving.Log().find("handing task"), std::string::npos)
      << "a task of milliseconds was handed back instead of finished within 2 s";
  EXPECT_TRUE(WaitUntil(
      [&] { return c.process->Log().find("left: worker stopping") != std::string::npos; }, 5s));

  ExpectSucceedsLike(client, job_id, reference);
  EXPECT_EQ(client.Workers().size(), 1u);
}

TEST_F(ServiceTest, AWorkerStoppedWithSigtermAndNoGraceHandsItsTaskBack) {
  const fs::path reference = Reference(kLongJob);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  ChildProcess& leaving = StartWorker("worker1", c.workers, {"--grace", "0"});
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  const std::string job_id = SubmitDetached(kLongJob, c.clients);
  WaitForProgress(client, job_id);
  ASSERT_TRUE(leaving.Kill(SIGTERM));
  const auto status = leaving.Wait(3s);
  ASSERT_TRUE(status) << "still running";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << ChildProcess::Describe(*status);
  // A task it gave back is the coordinator's to give to another, at once.
  static const std::regex kHandedBack(R"(handing task (t-\d+) back)");
  std::smatch handed;
  const std::string worker_log = leaving.Log();
  if (std::regex_search(worker_log, handed, kHandedBack)) {
    const std::string task = handed[1];
    EXPECT_TRUE(WaitUntil(
        [&] {
          return c.process->Log().find("(its task " + task + " goes to another)") !=
                 std::string::npos;
        },
        5s));
  }
  ExpectSucceedsLike(client, job_id, reference);
}

// ---- Bad input ----

// Sends `frames` and expects an ErrorReply with `code`; returns it.
proto::ClientReply ExpectRefused(RawDealer& raw, const std::vector<std::string>& frames,
                                 proto::ErrorCode code, const std::string& what) {
  raw.Send(frames);
  const auto reply = raw.Receive(10s);
  if (!reply) {
    ADD_FAILURE() << what << ": no answer";
    return {};
  }
  EXPECT_EQ(reply->size(), 1u) << what;
  const std::string& frame = reply->front();
  const proto::ClientReply decoded = evoslam::DecodeClientReply(AsBytes(frame));
  EXPECT_TRUE(decoded.has_error()) << what;
  EXPECT_EQ(decoded.error().code(), code) << what << ": " << decoded.error().message();
  return decoded;
}

std::string RandomBytes(std::mt19937& rng, std::size_t size) {
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  return bytes;
}

TEST_F(ServiceTest, TheClientSocketAnswersBadInputWithTheRightErrorCodes) {
  const CoordinatorProcess c = StartCoordinator("coordinator", {"--max-message-mb", "1"});
  StartWorker("worker1", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 1);
  RawDealer raw(context_, c.clients);

  proto::ClientRequest status;
  status.set_request_id(7);
  status.mutable_status()->set_job_id("job-123456789");
  const std::string valid = evoslam::Encode(status);
  // Cut inside the job id, the last field: the rest can no longer be parsed.
  ExpectRefused(raw, {valid.substr(0, valid.size() - 3)}, proto::ERROR_CODE_MALFORMED,
                "a truncated frame");
  // The valid frame itself is answered, by its id: the socket still works.
  {
    raw.Send({valid});
    const auto reply = raw.Receive(10s);
    ASSERT_TRUE(reply);
    const proto::ClientReply r = evoslam::DecodeClientReply(AsBytes(reply->front()));
    EXPECT_EQ(r.request_id(), 7u);
    EXPECT_EQ(r.error().code(), proto::ERROR_CODE_UNKNOWN_JOB);
  }

  std::mt19937 rng(20261201);
  for (int i = 0; i < 20; ++i) {
    raw.Send({RandomBytes(rng, 1 + rng() % 300)});
    const auto reply = raw.Receive(10s);
    ASSERT_TRUE(reply) << "random frame " << i << ": no answer";
    const proto::ClientReply r = evoslam::DecodeClientReply(AsBytes(reply->front()));
    ASSERT_TRUE(r.has_error()) << "random frame " << i;
    // Bytes that happen to parse carry no version, or a wrong one.
    EXPECT_TRUE(r.error().code() == proto::ERROR_CODE_MALFORMED ||
                r.error().code() == proto::ERROR_CODE_BAD_VERSION)
        << "random frame " << i << ": " << r.error().message();
  }

  proto::ClientRequest big;
  big.set_request_id(8);
  big.mutable_upload()->set_name("big.clf");
  big.mutable_upload()->set_content(std::string(std::size_t{3} << 19, 'x'));  // 1.5 MiB
  big.mutable_upload()->set_sha256(evoslam::Sha256Hex(big.upload().content()));
  ExpectRefused(raw, {evoslam::Encode(big)}, proto::ERROR_CODE_TOO_LARGE,
                "a frame over --max-message-mb 1");

  proto::ClientRequest future;
  future.set_protocol_version(evoslam::kProtocolVersion + 1);
  future.set_request_id(9);
  future.mutable_jobs();
  const proto::ClientReply version =
      ExpectRefused(raw, {future.SerializeAsString()}, proto::ERROR_CODE_BAD_VERSION, "version 2");
  EXPECT_NE(version.error().message().find(std::to_string(evoslam::kProtocolVersion + 1)),
            std::string::npos)
      << version.error().message();
  ExpectRefused(raw, {""}, proto::ERROR_CODE_BAD_VERSION, "an empty frame");

  proto::ClientRequest jobs;
  jobs.set_request_id(10);
  jobs.mutable_jobs();
  ExpectRefused(raw, {evoslam::Encode(jobs), "x", "y"}, proto::ERROR_CODE_MALFORMED,
                "a message of 3 frames");
  proto::ClientRequest nothing;
  nothing.set_request_id(11);
  ExpectRefused(raw, {evoslam::Encode(nothing)}, proto::ERROR_CODE_MALFORMED,
                "an envelope with no request");

  proto::ClientRequest mismatch;
  mismatch.set_request_id(12);
  mismatch.mutable_upload()->set_name("log.clf");
  mismatch.mutable_upload()->set_content("these bytes");
  mismatch.mutable_upload()->set_sha256(evoslam::Sha256Hex("other bytes"));
  const proto::ClientReply hash =
      ExpectRefused(raw, {evoslam::Encode(mismatch)}, proto::ERROR_CODE_INVALID, "a wrong hash");
  EXPECT_EQ(hash.request_id(), 12u);

  // Submits: of datasets never uploaded, and with parameters that cannot work.
  proto::DatasetRef ghost;
  ghost.set_sha256(evoslam::Sha256Hex("never uploaded"));
  ghost.set_name("ghost.clf");
  const proto::DatasetRef map = client.Upload(Map());
  proto::ClientRequest unknown;
  unknown.set_request_id(13);
  *unknown.mutable_submit()->mutable_spec() = SpecFor(Job{}, ghost, map, Log(), Map());
  ExpectRefused(raw, {evoslam::Encode(unknown)}, proto::ERROR_CODE_UNKNOWN_DATASET,
                "a dataset never uploaded");

  const proto::DatasetRef log = client.Upload(Log());
  proto::ClientRequest bad;
  bad.set_request_id(14);
  *bad.mutable_submit()->mutable_spec() = SpecFor(Job{}, log, map, Log(), Map());
  bad.mutable_submit()->mutable_spec()->mutable_localize()->set_generations(0);
  ExpectRefused(raw, {evoslam::Encode(bad)}, proto::ERROR_CODE_INVALID, "zero generations");
  bad.mutable_submit()->mutable_spec()->mutable_localize()->set_fitness("f9");
  ExpectRefused(raw, {evoslam::Encode(bad)}, proto::ERROR_CODE_INVALID, "fitness f9");
  EXPECT_TRUE(client.Jobs().empty()) << "a refused submit left a job behind";
  EXPECT_TRUE(c.process->Alive());

  // Far over the limit, ZeroMQ drops the connection before the memory is spent: no answer, and
  // the coordinator goes on.
  {
    RawDealer flood(context_, c.clients);
    flood.Send({std::string(std::size_t{3} << 20, 'x')});
    EXPECT_FALSE(flood.Receive(1s));
  }
  EXPECT_TRUE(c.process->Alive());

  const Job job{.scans = Scans(20)};
  const CommandResult r = Cli(RemoteArgs(job, Path("after"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(job), Path("after"));
  EXPECT_TRUE(c.process->Alive());
}

TEST_F(ServiceTest, TheWorkerSocketDropsGarbageAndTheServiceGoesOn) {
  const CoordinatorProcess c = StartCoordinator("coordinator", {"--max-message-mb", "1"});
  {
    RawDealer raw(context_, c.workers);
    proto::WorkerMessage ready;
    ready.mutable_ready()->set_hostname("a-host-name-long-enough-to-cut");
    ready.mutable_ready()->set_threads(4);
    const std::string valid = evoslam::Encode(ready);
    raw.Send({valid.substr(0, valid.size() - 5)});
    std::mt19937 rng(7);
    for (int i = 0; i < 20; ++i) raw.Send({RandomBytes(rng, 1 + rng() % 300)});
    proto::WorkerMessage big;
    big.mutable_disconnect()->set_reason(std::string(std::size_t{3} << 19, 'x'));  // 1.5 MiB
    raw.Send({evoslam::Encode(big)});
    proto::WorkerMessage future = ready;
    future.set_protocol_version(evoslam::kProtocolVersion + 1);
    raw.Send({future.SerializeAsString()});
    raw.Send({valid, "x", "y"});
    raw.Send({""});
    // Well-formed, but from a worker that never said Ready: a result for a task it was never
    // given, and a fetch.
    proto::WorkerMessage result;
    result.mutable_result()->set_task_id("t-1");
    result.mutable_result()->mutable_error()->set_message("made up");
    raw.Send({evoslam::Encode(result)});
    proto::WorkerMessage fetch;
    fetch.mutable_fetch()->set_sha256(evoslam::Sha256Hex("never uploaded"));
    raw.Send({evoslam::Encode(fetch)});

    // Each was read and dropped, the unknown worker told to say Ready first.
    for (const char* said :
         {"is not a valid protocol buffer", "is over the limit", "speaks protocol version 2",
          "dropped a message of 4 frames", "dropped a late answer for t-1"}) {
      EXPECT_TRUE(WaitUntil([&] { return c.process->Log().find(said) != std::string::npos; }, 10s))
          << "the coordinator's log never says '" << said << "'";
    }
    bool told = false;
    while (auto frames = raw.Receive(1s)) {
      const std::string& f = frames->front();
      told |= evoslam::DecodeCoordinatorMessage(AsBytes(f)).has_disconnect();
    }
    EXPECT_TRUE(told) << "an unknown worker was not asked to say Ready";
  }
  EXPECT_TRUE(c.process->Alive());
  {
    RawDealer flood(context_, c.workers);
    flood.Send({std::string(std::size_t{3} << 20, 'x')});
    std::this_thread::sleep_for(500ms);
  }
  EXPECT_TRUE(c.process->Alive());

  StartWorker("worker1", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 1);
  const Job job{.scans = Scans(20)};
  const CommandResult r = Cli(RemoteArgs(job, Path("after"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(job), Path("after"));
  EXPECT_TRUE(c.process->Alive());
}

// A worker that answers for a task it does not hold, or answers after the coordinator gave its
// task to another, is not listened to: here the answers are failures, which would fail the job
// if they were taken.
TEST_F(ServiceTest, AnswersFromAWorkerThatDoesNotHoldTheTaskAreDropped) {
  const Job job{.scans = Scans(20)};
  const fs::path reference = Reference(job);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  auto client = Client(c.clients);
  const std::string job_id = SubmitDetached(job, c.clients);

  const auto fake_worker = FakeWorker(c.workers);
  RawDealer& fake = *fake_worker;
  const std::optional<proto::Task> task = AwaitTask(fake);
  ASSERT_TRUE(task);
  const auto failure = [](const std::string& task_id) {
    proto::WorkerMessage m;
    m.mutable_result()->set_task_id(task_id);
    m.mutable_result()->mutable_error()->set_message("this answer must not be taken");
    return evoslam::Encode(m);
  };
  const auto logged = [&](const std::string& what) {
    return WaitUntil([&] { return c.process->Log().find(what) != std::string::npos; }, 10s);
  };
  fake.Send({failure("t-999999")});
  EXPECT_TRUE(logged("dropped an answer for t-999999"));
  // Then it falls silent, holding its task, until the coordinator gives up on it.
  EXPECT_TRUE(logged("its task " + task->task_id() + " goes to another"));
  fake.Send({failure(task->task_id())});
  EXPECT_TRUE(logged("dropped a late answer for " + task->task_id()));
  EXPECT_FALSE(Finished(client.Status(job_id))) << Describe(client.Status(job_id));

  StartWorker("worker1", c.workers);
  ExpectSucceedsLike(client, job_id, reference);
}

// A worker dropped for silence and then woken answers two requests for a new start with two
// Readys: the coordinator's when it dropped it, and the one it gets for the heartbeat it sends
// on waking. The second comes in after the coordinator has handed it a task again; played here
// by a fake worker, it must not take that task back and send another to a busy worker (which
// would refuse it, and the refusal would fail the job).
TEST_F(ServiceTest, ARepeatedReadyDoesNotTakeBackTheTaskOnItsWayToTheWorker) {
  const Job job{.scans = Scans(10)};
  const fs::path reference = Reference(job);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  auto client = Client(c.clients);
  const std::string job_id = SubmitDetached(job, c.clients);

  RawDealer fake(context_, c.workers);
  proto::WorkerMessage ready;
  ready.mutable_ready()->set_hostname("fake");
  ready.mutable_ready()->set_threads(1);
  proto::WorkerMessage heartbeat;
  heartbeat.mutable_heartbeat();
  // The tasks that come within `wait`, while the fake keeps its heartbeats going.
  const auto tasks_within = [&](Clock::duration wait) {
    std::vector<proto::Task> tasks;
    const Clock::time_point until = Clock::now() + wait;
    while (Clock::now() < until) {
      fake.Send({evoslam::Encode(heartbeat)});
      if (auto frames = fake.Receive(50ms)) {
        const auto m = evoslam::DecodeCoordinatorMessage(AsBytes(frames->front()));
        if (m.has_task()) tasks.push_back(m.task());
      }
    }
    return tasks;
  };
  fake.Send({evoslam::Encode(ready)});
  std::vector<proto::Task> first;
  ASSERT_TRUE(WaitUntil(
      [&] {
        first = tasks_within(50ms);
        return !first.empty();
      },
      10s));
  ASSERT_EQ(first.size(), 1u);

  fake.Send({evoslam::Encode(ready)});
  const std::vector<proto::Task> more = tasks_within(1s);
  EXPECT_TRUE(more.empty()) << "a worker that holds " << first[0].task_id() << " was sent "
                            << more.size() << " more, the first " << more[0].task_id();
  const auto workers = client.Workers();
  ASSERT_EQ(workers.size(), 1u);
  EXPECT_TRUE(workers[0].busy());
  EXPECT_EQ(workers[0].worker_id(), "w-1") << "a repeated Ready made a new worker";

  // It leaves, handing its task back; a real worker does the job.
  proto::WorkerMessage bye;
  bye.mutable_disconnect()->set_reason("test over");
  bye.mutable_disconnect()->set_handed_back_task_id(first[0].task_id());
  fake.Send({evoslam::Encode(bye)});
  StartWorker("worker1", c.workers);
  ExpectSucceedsLike(client, job_id, reference);
}

// A worker that refuses a task because it is busy (with work the coordinator no longer counts
// on) does not fail the job: the task goes to another worker, and the busy one is asked to
// introduce itself again.
TEST_F(ServiceTest, ABusyWorkersRefusalSendsTheTaskElsewhere) {
  const Job job{.scans = Scans(10)};
  const fs::path reference = Reference(job);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  auto client = Client(c.clients);
  const std::string job_id = SubmitDetached(job, c.clients);

  const auto fake_worker = FakeWorker(c.workers);
  RawDealer& fake = *fake_worker;
  const std::optional<proto::Task> task = AwaitTask(fake);
  ASSERT_TRUE(task);
  proto::WorkerMessage busy;
  busy.mutable_result()->set_task_id(task->task_id());
  busy.mutable_result()->mutable_error()->set_code(proto::ERROR_CODE_QUEUE_FULL);
  busy.mutable_result()->mutable_error()->set_message("worker busy");
  fake.Send({evoslam::Encode(busy)});
  // It is told to start again, and no longer counts as a worker until it does.
  bool told = false;
  ASSERT_TRUE(WaitUntil(
      [&] {
        while (auto frames = fake.Receive(10ms)) {
          told |= evoslam::DecodeCoordinatorMessage(AsBytes(frames->front())).has_disconnect();
        }
        return told;
      },
      10s));
  EXPECT_TRUE(client.Workers().empty());

  StartWorker("worker1", c.workers);
  ExpectSucceedsLike(client, job_id, reference);
}

// ---- SLAM ----

// Paper 002's SLAM as a job: a drive through the simulated office cluster whose odometry drifts,
// long enough for periodic global searches and a loop (under the sanitizers, periodic searches
// alone), with searches small enough that the job takes seconds.
class SlamJobTest : public ServiceTest {
 protected:
  static constexpr std::uint64_t kSeed = 3;
  static constexpr std::size_t kScans = Scans(200);

  void SetUp() override {
    evoslam::SimulationOptions sim;
    sim.laser.beams = 61;
    sim.noise.odometry.rotation_bias = 0.02;
    sim.max_scans = kScans;
    evoslam::WriteCarmen(evoslam::Simulate(evoslam::BuiltinWorld("office-cluster"), sim),
                         DriveLog());
    // The true motion between scans ten apart, stamped as the log reads back.
    std::ofstream relations(DriveRelations());
    relations.precision(17);
    const evoslam::Dataset drive = evoslam::ReadCarmen(DriveLog());
    for (std::size_t i = 0; i + 10 < drive.scans.size(); i += 10) {
      const evoslam::LaserScan &a = drive.scans[i], &b = drive.scans[i + 10];
      const evoslam::Pose2 delta = a.true_pose->inverse() * *b.true_pose;
      relations << a.timestamp << ' ' << b.timestamp << ' ' << delta.x() << ' ' << delta.y()
                << " 0 0 0 " << delta.theta() << '\n';
    }
  }

  fs::path DriveLog() const { return dir_ / "drive.clf"; }
  fs::path DriveRelations() const { return dir_ / "drive.relations"; }

  static proto::SlamParams Params() {
    proto::SlamParams p;
    p.set_log("drive.clf");
    p.set_seed(kSeed);
    p.set_islands(2);
    p.set_generations(20);  // two epochs: migrants travel between them
    p.set_partitions(4);
    p.set_global_every(static_cast<std::uint32_t>(Scans(100)));
    p.set_check_interval_scans(1);  // the drive's one revisit lasts a few scans
    // Ten times 002's PSO iterations: the local search then lasts about a second, a window wide
    // enough for a test to catch the job part-way between its polls.
    p.set_local_iterations(300);
    // A local search of one fixed cube per step, unrefined, leaves the revisit off the map, and its
    // match, not distinct enough to be trusted in a real run, is let through: here it only has to
    // start a loop's search, whose tasks the service must run as RunRssSlam does.
    p.set_local_recentres(0);
    p.set_local_turn_error_per_rad(0.0);
    p.set_local_carried_turn_error(0.0);
    p.set_local_refine_iterations(0);
    p.set_min_distinctness(0.0);
    return p;
  }

  // The job's files as RunRssSlam makes them in this process, its global searches on local
  // threads: what the service must hand back.
  fs::path SlamReference() {
    const fs::path out = dir_ / "slam-reference";
    const evoslam::Dataset drive = evoslam::ReadCarmen(DriveLog());
    const evoslam::RssSlamResult result =
        evoslam::RunRssSlam(drive, evoslam::RssSlamParamsFromProto(Params()), kSeed);
    EXPECT_FALSE(result.global_searches.empty()) << "no global search: the job sends no task";
    if (kScaleDown == 1) {
      EXPECT_FALSE(result.loops.empty()) << "no loop: none is searched";
    }
    // Named as the service names them: by the path they were uploaded from.
    const evoslam::NamedRelations relations{DriveRelations().string(),
                                            evoslam::ReadRelations(DriveRelations())};
    fs::create_directories(out);
    for (const proto::ResultFile& f :
         evoslam::SlamOutputs(drive, evoslam::CompleteSlamParams(Params()), result, relations, 1)) {
      std::ofstream(out / f.name(), std::ios::binary) << f.content();
    }
    return out;
  }

  // Submits the job as a client does: datasets uploaded, seed and islands in the spec. An empty
  // `relations` is the drive's.
  std::string SubmitSlam(evoslam::ServiceClient& client, const proto::SlamParams& params = Params(),
                         const fs::path& relations = {}) {
    proto::JobSpec spec;
    spec.set_kind(proto::JOB_KIND_SLAM);
    *spec.mutable_log() = client.Upload(DriveLog());
    *spec.mutable_relations() = client.Upload(relations.empty() ? DriveRelations() : relations);
    *spec.mutable_slam() = params;
    spec.mutable_slam()->clear_seed();
    spec.mutable_slam()->clear_islands();
    spec.set_seed(kSeed);
    spec.set_islands(2);
    return client.Submit(spec);
  }

  static void ExpectSameSlamOutputs(const fs::path& expected, const fs::path& actual) {
    ExpectSameTrajectory(expected, actual);
    EXPECT_TRUE(ReadAll(expected / "map.pgm") == ReadAll(actual / "map.pgm")) << "map.pgm differs";
    EXPECT_EQ(StableReport(expected / "report.json"), StableReport(actual / "report.json"));
    EXPECT_NE(ReadAll(actual / "report.json").find("\"relation_errors\""), std::string::npos)
        << "the relations were not scored";
  }
};

TEST_F(SlamJobTest, OnTwoWorkerProcessesItWritesWhatRunRssSlamWritesInProcess) {
  const fs::path reference = SlamReference();
  const CoordinatorProcess c = StartCoordinator("coordinator");
  const std::vector<ChildProcess*> workers = {&StartWorker("worker1", c.workers),
                                              &StartWorker("worker2", c.workers)};
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  // A bad parameter is refused at submit, by name.
  proto::SlamParams bad = Params();
  bad.add_sigma(0.3);
  try {
    SubmitSlam(client, bad);
    ADD_FAILURE() << "a SLAM job with one sigma value was accepted";
  } catch (const evoslam::ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_INVALID);
    EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos) << e.what();
  }
  // A malformed relations file fails the job, by name and line, before a scan is searched.
  std::ofstream(Path("bad.relations")) << "1.0 2.0 0.5\n";
  const proto::JobStatus failed =
      WaitForEnd(client, SubmitSlam(client, Params(), Path("bad.relations")));
  EXPECT_EQ(failed.state(), proto::JOB_STATE_FAILED) << Describe(failed);
  EXPECT_NE(failed.error().find("bad.relations:1"), std::string::npos) << Describe(failed);
  EXPECT_EQ(failed.done(), 0u) << Describe(failed);

  const std::string job_id = SubmitSlam(client);
  const proto::JobStatus end = WaitForEnd(client, job_id);
  ASSERT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
  FetchResult(client, job_id, Path("remote"));
  ExpectSameSlamOutputs(reference, Path("remote"));
  // The global searches' islands ran on both processes: each fetched the log. Their logs tell
  // even when a loaded machine made the coordinator drop and readmit a worker, which starts its
  // task count afresh.
  for (ChildProcess* w : workers) {
    EXPECT_NE(w->Log().find("fetching dataset " + DriveLog().string()), std::string::npos)
        << w->log_path();
  }
}

TEST_F(SlamJobTest, ItResumesFromItsCheckpointAfterTheCoordinatorIsKilledAndRestarted) {
  const fs::path reference = SlamReference();
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  std::string job_id;
  proto::JobStatus before;
  {
    auto client = Client(c.clients);
    WaitForWorkers(client, 2);
    job_id = SubmitSlam(client);
    before = WaitForProgress(client, job_id, kScans / 3, "local search");
  }
  const CoordinatorProcess restarted = KillAndResume(c, job_id, before);
  ASSERT_FALSE(HasFailure());
  auto client = Client(restarted.clients);
  FetchResult(client, job_id, Path("result"));
  ExpectSameSlamOutputs(reference, Path("result"));
}

// ---- CURVE ----

TEST_F(ServiceTest, WithCurveOnlyTheListedKeysAreServed) {
  const std::string keys = Path("keys");
  for (const char* name : {"coordinator", "worker", "client", "stranger"}) {
    const CommandResult k = Cli({"keygen", "--name", name, "--out", keys});
    ASSERT_EQ(k.exit_code, 0) << k.output;
  }
  const auto key = [&](const std::string& file) { return keys + "/" + file; };
  const CoordinatorProcess c = StartCoordinator(
      "coordinator", {"--curve-secret-key", key("coordinator.key"), "--client-keys",
                      key("client.pub"), "--worker-keys", key("worker.pub")});
  StartWorker("worker", c.workers,
              {"--curve-server-key", key("coordinator.pub"), "--curve-key", key("worker.key")});
  // A worker whose key is not listed never gets in.
  StartWorker("stranger-worker", c.workers,
              {"--curve-server-key", key("coordinator.pub"), "--curve-key", key("stranger.key")});
  const std::vector<std::string> as_client = {"--coordinator",      c.clients,
                                              "--curve-server-key", key("coordinator.pub"),
                                              "--curve-key",        key("client.key")};
  const auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };

  const Job job{.scans = Scans(20)};
  std::vector<std::string> localize = LocalizeArgs(job, Path("remote"));
  localize.insert(localize.end(), as_client.begin(), as_client.end());
  const CommandResult r = Cli(localize);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(job), Path("remote"));
  const CommandResult workers = Cli(with({"workers"}, as_client));
  ASSERT_EQ(workers.exit_code, 0) << workers.output;
  EXPECT_EQ(Count(workers.output, " threads "), 1u) << workers.output;

  // Refused clients hear nothing at all, and say so when their time is up.
  const std::vector<std::pair<std::string, std::vector<std::string>>> refused = {
      {"no CURVE", {"--coordinator", c.clients}},
      {"an unlisted key",
       {"--coordinator", c.clients, "--curve-server-key", key("coordinator.pub"), "--curve-key",
        key("stranger.key")}},
      {"a worker's key",
       {"--coordinator", c.clients, "--curve-server-key", key("coordinator.pub"), "--curve-key",
        key("worker.key")}},
  };
  for (const auto& [what, args] : refused) {
    const CommandResult no = Cli(with(with({"jobs"}, args), {"--timeout", "2"}), 20s);
    EXPECT_NE(no.exit_code, 0) << what << ": " << no.output;
    EXPECT_NE(no.output.find("no answer from the coordinator"), std::string::npos)
        << what << ": " << no.output;
    EXPECT_LT(no.seconds, 2 + 5.0) << what;
    EXPECT_TRUE(c.process->Alive());
  }
  EXPECT_NE(c.process->Log().find("is not accepted"), std::string::npos);

  const CommandResult jobs = Cli(with({"jobs"}, as_client));
  ASSERT_EQ(jobs.exit_code, 0) << jobs.output;
  EXPECT_NE(jobs.output.find("succeeded"), std::string::npos) << jobs.output;
}

// ---- Load ----

// (Twenty jobs under the sanitizers.)
TEST_F(ServiceTest, TwoHundredJobsFromTwentyClientsEachFinishExactlyOnce) {
  // Two seeds, so that a result handed to the wrong job would show.
  const std::vector<Job> tiny = {{.scans = 3, .optimizer = "de", .gen = 5, .pop = 10, .seed = 1},
                                 {.scans = 3, .optimizer = "de", .gen = 5, .pop = 10, .seed = 2}};
  std::vector<std::string> expected;
  for (const Job& job : tiny) expected.push_back(ReadAll(Reference(job) / "trajectory.txt"));
  ASSERT_NE(expected[0], expected[1]);

  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);
  const proto::DatasetRef log = client.Upload(Log());
  const proto::DatasetRef map = client.Upload(Map());

  constexpr int kClients = 20, kJobsEach = 10 / static_cast<int>(kScaleDown);
  std::mutex mutex;
  std::map<std::string, std::size_t> seed_of;  // job id -> index in `tiny`
  std::size_t accepted = 0;
  std::vector<std::string> errors;
  {
    std::vector<std::jthread> clients;
    for (int t = 0; t < kClients; ++t) {
      clients.emplace_back([&, t] {
        try {
          auto mine = Client(c.clients, 30);
          for (int j = 0; j < kJobsEach; ++j) {
            const std::size_t which = static_cast<std::size_t>(t + j) % tiny.size();
            const std::string id = mine.Submit(SpecFor(tiny[which], log, map, Log(), Map()));
            std::lock_guard lock(mutex);
            seed_of[id] = which;
            ++accepted;
          }
        } catch (const std::exception& e) {
          std::lock_guard lock(mutex);
          errors.push_back(e.what());
        }
      });
    }
  }
  ASSERT_TRUE(errors.empty()) << errors.size() << " submits failed, first: " << errors.front();
  ASSERT_EQ(accepted, std::size_t{kClients * kJobsEach});
  EXPECT_EQ(seed_of.size(), accepted) << "job ids were given twice";

  std::vector<proto::JobStatus> jobs;
  ASSERT_TRUE(WaitUntil(
      [&] {
        jobs = client.Jobs();
        return std::all_of(jobs.begin(), jobs.end(), Finished);
      },
      90s, 200ms));
  ASSERT_EQ(jobs.size(), accepted);
  const std::string log_text = c.process->Log();
  for (const proto::JobStatus& s : jobs) {
    ASSERT_TRUE(seed_of.contains(s.job_id())) << s.job_id() << " was never submitted";
    EXPECT_EQ(s.state(), proto::JOB_STATE_SUCCEEDED) << Describe(s);
    EXPECT_EQ(Count(log_text, " " + s.job_id() + ": succeeded\n"), 1u) << s.job_id();
    EXPECT_EQ(Count(log_text, " " + s.job_id() + ": running\n"), 1u) << s.job_id();
  }
  EXPECT_EQ(Count(log_text, ": failed"), 0u);
  std::size_t checked = 0;
  for (const auto& [id, which] : seed_of) {
    for (const proto::ResultFile& f : client.Result(id)) {
      if (f.name() != "trajectory.txt") continue;
      EXPECT_EQ(f.content(), expected[which]) << id << " has another job's result";
      ++checked;
    }
  }
  EXPECT_EQ(checked, accepted);
}

}  // namespace
