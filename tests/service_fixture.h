#ifndef EVOSLAM_TESTS_SERVICE_FIXTURE_H_
#define EVOSLAM_TESTS_SERVICE_FIXTURE_H_

// For the service's acceptance tests (cluster_*_test.cc): real evoslam-coordinator,
// evoslam-worker and evoslam processes on the loopback interface, driven the way an operator
// would drive them. A job's result must not depend on where it ran or on what went wrong
// meanwhile: every finished job is compared with the embedded run (`evoslam localize` without
// --coordinator) of the same command line.

#include <gtest/gtest.h>
#include <zmq.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/localization/localize_params.h"
#include "common/protocol/wire.h"
#include "common/protocol/zmq_io.h"
#include "common/service/service_client.h"
#include "common/transform/angle_units.h"
#include "common/util/temp_dir.h"
#include "tests/process_testing.h"

namespace evoslam::service_test {

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

inline std::string ReadAll(const fs::path& path) {
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

inline std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

inline std::span<const std::byte> AsBytes(const std::string& frame) {
  return {reinterpret_cast<const std::byte*>(frame.data()), frame.size()};
}

inline bool Finished(const proto::JobStatus& s) {
  return s.state() == proto::JOB_STATE_SUCCEEDED || s.state() == proto::JOB_STATE_FAILED ||
         s.state() == proto::JOB_STATE_CANCELLED;
}

// The error a call gets; fails the test when it succeeds.
template <typename Call>
ProtocolError RefusalOf(Call call, const std::string& what) {
  try {
    call();
  } catch (const ProtocolError& e) {
    return e;
  }
  ADD_FAILURE() << what << ": accepted";
  return ProtocolError(proto::ERROR_CODE_UNSPECIFIED, "");
}

inline std::string Describe(const proto::JobStatus& s) {
  return s.job_id() + " state " + std::to_string(s.state()) + " " + s.phase() + " " +
         std::to_string(s.done()) + "/" + std::to_string(s.total()) +
         (s.error().empty() ? "" : " error: " + s.error());
}

// report.json without what depends on the machine and the moment: timings and thread counts
// (a SLAM report's phase times and global search seconds among them).
inline std::string StableReport(const fs::path& path) {
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
inline const Job kLongJob{.scans = Scans(60), .optimizer = "island", .islands = 4, .gen = 50};

// The job the command line `LocalizeArgs(job, ...)` describes, built as cli/localize_command.cc
// builds it, on datasets already uploaded.
inline proto::JobSpec SpecFor(const Job& job, const proto::DatasetRef& log,
                              const proto::DatasetRef& map, const fs::path& log_path,
                              const fs::path& map_path) {
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
  // Converted as the command line converts them, so that the radians have the same bits.
  e.heading_half_window = evoslam::Radians(30.0);
  e.heading_step = evoslam::Radians(0.5);
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

// A job submitted to a coordinator of its own, and what a test follows and checks it with.
struct SubmittedJob {
  CoordinatorProcess coordinator;
  evoslam::ServiceClient client;  // on the coordinator's client socket
  std::string id;
  fs::path reference;  // the embedded run's outputs: what the job must write
};

// A job under way on two workers, for a test to disturb.
struct JobUnderWay : SubmittedJob {
  ChildProcess& worker1;
  ChildProcess& worker2;
  proto::JobStatus progress;  // its status when first seen under way
};

class ServiceTest : public ::testing::Test {
 protected:
  // One small simulated world for the whole binary (ctest runs each test in a process of its
  // own, so there it is made once per test; it takes a few milliseconds), and the embedded runs'
  // outputs that tests compare the service's with.
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
                                     "--generations",
                                     std::to_string(job.gen),
                                     "--population",
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

  // The job's outputs as the embedded run writes them: what every run of it must write. Kept
  // beside the world, so that tests run in one process (the sanitizer pass runs a binary's tests
  // in a few) compute each job's reference once.
  fs::path Reference(const Job& job) {
    const fs::path out = world_->path() / ("reference-" + job.Key());
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
    static const std::regex kJobId(R"((^|\n)(job-[0-9a-f]+)\n)");
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

  // Waits until the job has done at least `scans` scans of its `phase` ("slam" for a SLAM job)
  // but not all of them, and returns its status then. Throws when it finishes first:
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

  // Starts `job` on a new coordinator's two workers, "worker1" (started with `worker1_extra`)
  // and "worker2", and returns once it is under way; throws when it ends before it can be
  // disturbed.
  JobUnderWay StartOnTwoWorkers(const Job& job,
                                const std::vector<std::string>& worker1_extra = {}) {
    fs::path reference = Reference(job);
    const CoordinatorProcess coordinator = StartCoordinator("coordinator");
    ChildProcess& worker1 = StartWorker("worker1", coordinator.workers, worker1_extra);
    ChildProcess& worker2 = StartWorker("worker2", coordinator.workers);
    evoslam::ServiceClient client = Client(coordinator.clients);
    WaitForWorkers(client, 2);
    std::string id = SubmitDetached(job, coordinator.clients);
    proto::JobStatus progress = WaitForProgress(client, id);
    return {{coordinator, std::move(client), std::move(id), std::move(reference)},
            worker1,
            worker2,
            std::move(progress)};
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

  // Submits `job` to a new coordinator that has no worker yet: the first to say Ready, often one
  // the test plays, is handed its first task.
  SubmittedJob SubmitWithNoWorkers(const Job& job) {
    fs::path reference = Reference(job);
    const CoordinatorProcess coordinator = StartCoordinator("coordinator");
    evoslam::ServiceClient client = Client(coordinator.clients);
    std::string id = SubmitDetached(job, coordinator.clients);
    return {coordinator, std::move(client), std::move(id), std::move(reference)};
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

  static inline evoslam::TempDir* world_ = nullptr;
  zmq::context_t context_;
  evoslam::TempDir dir_;
  // Destroyed before dir_ (members go in reverse order): every process is killed before its
  // folder is removed.
  std::vector<std::unique_ptr<ChildProcess>> processes_;
  int cli_runs_ = 0;
};

}  // namespace evoslam::service_test

#endif  // EVOSLAM_TESTS_SERVICE_FIXTURE_H_
