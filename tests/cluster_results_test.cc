// A job on the service gives what the embedded run gives, and every job of many finishes once.

#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

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
}  // namespace evoslam::service_test
