// Faults injected while a job runs (kill -9, SIGSTOP, SIGTERM of workers and the coordinator):
// the job still ends with the embedded run's result.

#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

TEST_F(ServiceTest, AJobOutlivesAWorkerKilledMidJob) {
  JobUnderWay job = StartOnTwoWorkers(kLongJob);
  ChildProcess& victim = job.worker1;
  ASSERT_TRUE(victim.Kill(SIGKILL));
  ASSERT_TRUE(victim.Wait(5s));
  // The coordinator says so: when it finds the connection closed, or the worker silent.
  EXPECT_TRUE(WaitUntil(
      [&] {
        const std::string log = job.coordinator.process->Log();
        return log.find("is gone (its connection is closed)") != std::string::npos ||
               log.find("is lost (silent or overdue)") != std::string::npos;
      },
      10s));
  const proto::JobStatus end = WaitForEnd(job.client, job.id);
  ASSERT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
  EXPECT_EQ(end.done(), end.total());
  EXPECT_LT(job.progress.done(), end.total());
  FetchResult(job.client, job.id, Path("result"));
  ExpectSameTrajectory(job.reference, Path("result"));
  EXPECT_TRUE(WaitUntil([&] { return job.client.Workers().size() == 1; }, 5s));
  EXPECT_TRUE(job.coordinator.process->Alive());
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
  JobUnderWay job = StartOnTwoWorkers(kLongJob);
  ChildProcess& paused = job.worker1;
  ChildProcess& other = job.worker2;
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
        log = job.coordinator.process->Log();
        return std::regex_search(log, lost, kLost);
      },
      10s));
  const std::string task = lost[2];
  ExpectSucceedsLike(job.client, job.id, job.reference);
  EXPECT_EQ(job.client.Workers().size(), 1u);

  ASSERT_TRUE(paused.Kill(SIGCONT));
  // It says Ready again and is listed again.
  CommandResult listed;
  EXPECT_TRUE(WaitUntil(
      [&] {
        listed = Cli({"workers", "--coordinator", job.coordinator.clients, "--timeout", "10"});
        return listed.exit_code == 0 && Count(listed.output, " done\n") == 2;
      },
      10s, 100ms))
      << listed.output;
  // Its answer to the task it held is never taken. Either the coordinator drops it (it no longer
  // knows the worker), or the worker, told by the coordinator that its task went elsewhere,
  // throws it away itself; which of the two comes first is a race between the worker's threads.
  const std::string coordinator_log = job.coordinator.process->Log();
  const bool dropped =
      coordinator_log.find("dropped a late answer for " + task) != std::string::npos ||
      coordinator_log.find("dropped an answer for " + task) != std::string::npos;
  const bool told = paused.Log().find("the coordinator asks for a new start") != std::string::npos;
  EXPECT_TRUE(dropped || told) << "the late answer to " << task << " went unnoticed";

  // The worker that came back does work: alone, it runs the next job.
  ASSERT_TRUE(other.Kill(SIGTERM));
  ASSERT_TRUE(other.Wait(10s));
  WaitForWorkers(job.client, 1);
  const Job small{.scans = Scans(10)};
  const CommandResult r = Cli(RemoteArgs(small, Path("after"), job.coordinator.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(small), Path("after"));
}

// A worker paused past its deadline and resumed while the job still runs comes back with a
// stale task in hand and a stale view of the coordinator; none of it may change the job.
TEST_F(ServiceTest, AWorkerPausedAndResumedMidJobDoesNotChangeItsResult) {
  Job longer = kLongJob;
  longer.scans = Scans(90);
  JobUnderWay job = StartOnTwoWorkers(longer);
  ChildProcess& paused = job.worker1;
  std::size_t rounds = 0;
  for (; rounds < 3 && !Finished(job.client.Status(job.id)); ++rounds) {
    ASSERT_TRUE(paused.Kill(SIGSTOP));
    ASSERT_TRUE(WaitUntil(
        [&] {
          return Count(job.coordinator.process->Log(), "is lost (silent or overdue)") > rounds;
        },
        10s));
    ASSERT_TRUE(paused.Kill(SIGCONT));
    ASSERT_TRUE(WaitUntil([&] { return job.client.Workers().size() == 2; }, 10s));
  }
  EXPECT_GE(rounds, 2u) << "the job ended too soon to be disturbed";
  ExpectSucceedsLike(job.client, job.id, job.reference);
}

TEST_F(ServiceTest, AWorkerStoppedWithSigtermFinishesItsTaskAndLeavesCleanly) {
  JobUnderWay job = StartOnTwoWorkers(kLongJob, {"--grace", "2"});
  ChildProcess& leaving = job.worker1;
  ASSERT_TRUE(leaving.Kill(SIGTERM));
  const auto status = leaving.Wait(2s + 3s);  // its grace, and a margin for a loaded machine
  ASSERT_TRUE(status) << "still running after its grace";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << ChildProcess::Describe(*status);
  EXPECT_NE(leaving.Log().find("worker: left"), std::string::npos);
  EXPECT_EQ(leaving.Log().find("handing task"), std::string::npos)
      << "a task of milliseconds was handed back instead of finished within 2 s";
  EXPECT_TRUE(WaitUntil(
      [&] {
        return job.coordinator.process->Log().find("left: worker stopping") != std::string::npos;
      },
      5s));

  ExpectSucceedsLike(job.client, job.id, job.reference);
  EXPECT_EQ(job.client.Workers().size(), 1u);
}

TEST_F(ServiceTest, AWorkerStoppedWithSigtermAndNoGraceHandsItsTaskBack) {
  JobUnderWay job = StartOnTwoWorkers(kLongJob, {"--grace", "0"});
  ChildProcess& leaving = job.worker1;
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
          return job.coordinator.process->Log().find("(its task " + task + " goes to another)") !=
                 std::string::npos;
        },
        5s));
  }
  ExpectSucceedsLike(job.client, job.id, job.reference);
}

}  // namespace
}  // namespace evoslam::service_test
