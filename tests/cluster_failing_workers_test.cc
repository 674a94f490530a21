// Failures that are not a job's own: a stalled coordinator, a worker that cannot work, a worker
// that answers nonsense, a worker or a coordinator killed outright. No job may fail of them, and
// each is said in the coordinator's log.

#include <atomic>
#include <thread>

#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

// The folders a coordinator keeps its dataset copies in, under the test's TMPDIR.
std::size_t CoordinatorTempDirs(const fs::path& tmp) {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(tmp)) {
    n += entry.path().filename().string().starts_with("evoslam-coordinator-");
  }
  return n;
}

// Stopped for longer than its workers wait (SIGSTOP: a paused VM, a swapping host), the
// coordinator finds on resuming its workers gone to new connections and its sockets full of
// what the old ones said before. Neither the dead connections nor the stall may count against
// the job's tasks. (deploy/stall-trials.sh repeats this 20 times.)
TEST_F(ServiceTest, ACoordinatorStoppedForEightSecondsFailsNoJob) {
  // More workers than islands: idle workers' dead connections wait at the head of the line.
  const Job job{.scans = Scans(40), .optimizer = "island", .islands = 2, .gen = 50};
  const fs::path reference = Reference(job);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  for (int i = 1; i <= 6; ++i) StartWorker("worker" + std::to_string(i), c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 6);
  const std::string id = SubmitDetached(job, c.clients);
  WaitForProgress(client, id);
  ASSERT_TRUE(c.process->Kill(SIGSTOP));
  std::this_thread::sleep_for(8s);
  ASSERT_TRUE(c.process->Kill(SIGCONT)) << "the coordinator ended while stopped: "
                                        << ChildProcess::Describe(c.process->Wait(0s).value_or(0));
  ExpectSucceedsLike(client, id, reference);
  EXPECT_EQ(c.process->Log().find("giving up"), std::string::npos);
  EXPECT_NE(c.process->Log().find("the coordinator did not run for"), std::string::npos);
  EXPECT_TRUE(WaitUntil([&] { return client.Workers().size() == 6; }, 20s))
      << client.Workers().size() << " workers";
}

// A worker whose cache cannot be written fails every task through no fault of the tasks: they
// go to the healthy worker, and the broken one leaves the pool for a while.
TEST_F(ServiceTest, AWorkerThatCannotCacheDatasetsIsQuarantinedAndNoJobFails) {
  const Job first{.scans = Scans(10), .seed = 1}, second{.scans = Scans(10), .seed = 2};
  const fs::path reference1 = Reference(first), reference2 = Reference(second);
  const CoordinatorProcess c = StartCoordinator("coordinator");
  // Nobody, root included, can make folders in /proc/self.
  StartWorker("broken", c.workers, {"--cache-dir", "/proc/self"});
  StartWorker("healthy", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);
  for (const auto& [job, reference] : {std::pair{first, reference1}, {second, reference2}}) {
    const std::string out = Path("out-" + job.Key());
    const CommandResult r = Cli(RemoteArgs(job, out, c.clients));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    ExpectSameTrajectory(reference, out);
  }
  EXPECT_NE(c.process->Log().find("(quarantined): failed 3 tasks in a row"), std::string::npos);
  const CommandResult workers = Cli({"workers", "--coordinator", c.clients, "--timeout", "10"});
  ASSERT_EQ(workers.exit_code, 0) << workers.output;
  EXPECT_EQ(Count(workers.output, " done\n"), 2u) << workers.output;
  EXPECT_EQ(Count(workers.output, "quarantined for "), 1u) << workers.output;
  EXPECT_NE(workers.output.find("cannot cache dataset"), std::string::npos) << workers.output;
}

// A worker that answers each task with the task's own input (an island that never advanced)
// would stall its job for ever if its answers were taken.
TEST_F(ServiceTest, AWorkerEchoingItsTasksIsDroppedAndTheJobEndsAsEmbedded) {
  SubmittedJob job = SubmitWithNoWorkers({.scans = Scans(10)});
  std::unique_ptr<RawDealer> fake = FakeWorker(job.coordinator.workers);
  std::atomic<bool> done{false};
  std::atomic<int> echoed{0};
  // It keeps its heartbeats going and echoes every task it gets.
  std::thread echo([&] {
    proto::WorkerMessage beat;
    beat.mutable_heartbeat();
    while (!done) {
      fake->Send({evoslam::Encode(beat)});
      while (auto frames = fake->Receive(50ms)) {
        const auto m = evoslam::DecodeCoordinatorMessage(AsBytes(frames->front()));
        if (!m.has_task()) continue;
        proto::WorkerMessage answer;
        proto::TaskResult& r = *answer.mutable_result();
        r.set_task_id(m.task().task_id());
        if (m.task().has_evolve()) {
          *r.mutable_island()->mutable_island() = m.task().evolve().island();
        } else {
          *r.mutable_fitness() = m.task().evaluate().candidates();
        }
        fake->Send({evoslam::Encode(answer)});
        ++echoed;
      }
    }
  });
  const bool dropped = WaitUntil(
      [&] {
        return job.coordinator.process->Log().find("sent an invalid result") != std::string::npos;
      },
      20s);
  StartWorker("worker1", job.coordinator.workers);
  const proto::JobStatus end = WaitForEnd(job.client, job.id);
  const std::vector<proto::WorkerInfo> workers = job.client.Workers();
  done = true;
  echo.join();
  EXPECT_TRUE(dropped);
  ASSERT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
  EXPECT_EQ(echoed, 1) << "a worker that sent an invalid result was given more tasks";
  FetchResult(job.client, job.id, Path("result"));
  ExpectSameOutputs(job.reference, Path("result"));
  ASSERT_EQ(workers.size(), 2u);
  for (const proto::WorkerInfo& w : workers) {
    EXPECT_EQ(w.quarantine_reason().empty(), w.hostname() != "fake") << w.hostname();
  }
}

// A coordinator killed with -9 cannot remove its copies of the datasets; the next one started
// does.
TEST_F(ServiceTest, ACoordinatorKilledWithSigkillLeavesNoDatasetCopiesAfterTheNextStart) {
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  const Job job{.scans = Scans(5)};
  const CommandResult r = Cli(RemoteArgs(job, Path("out"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(CoordinatorTempDirs(dir_.path()), 1u);
  ASSERT_TRUE(c.process->Kill(SIGKILL));
  ASSERT_TRUE(c.process->Wait(5s));
  ASSERT_EQ(CoordinatorTempDirs(dir_.path()), 1u) << "nothing left behind to clean up";
  const CoordinatorProcess restarted = StartCoordinator("coordinator-restarted");
  EXPECT_EQ(CoordinatorTempDirs(dir_.path()), 1u)
      << "the dead coordinator's copies are still there";
  EXPECT_NE(restarted.process->Log().find("removed 1 temporary dataset folder"), std::string::npos);
}

}  // namespace
}  // namespace evoslam::service_test
