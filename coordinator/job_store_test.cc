#include "coordinator/job_store.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

proto::JobStatus Progress(const std::string& phase, std::uint64_t done, std::uint64_t total,
                          std::uint64_t evaluations) {
  proto::JobStatus s;
  s.set_phase(phase);
  s.set_done(done);
  s.set_total(total);
  s.set_evaluations(evaluations);
  return s;
}

proto::JobSpec LocalizeSpec(std::uint64_t seed) {
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_LOCALIZE);
  spec.mutable_log()->set_sha256(std::string(64, 'b'));
  spec.set_seed(seed);
  spec.mutable_localize()->set_optimizer("island");
  return spec;
}

class JobStoreTest : public ::testing::Test {
 protected:
  std::filesystem::path Db() const { return dir_.path() / "coordinator.db"; }
  TempDir dir_;
};

TEST_F(JobStoreTest, JobsKeepTheirSpecStateAndOrderAcrossReopening) {
  {
    JobStore store(Db());
    EXPECT_EQ(store.AddJob(LocalizeSpec(1), 100.0), "job-1");
    EXPECT_EQ(store.AddJob(LocalizeSpec(2), 101.0), "job-2");
    store.SetRunning("job-1", Progress("localize", 5, 40, 1234));
    EXPECT_TRUE(store.Finish("job-2", proto::JOB_STATE_FAILED, "scan 3: no map", 102.0));
    // A job ends once: neither a later success nor progress overrides how it ended.
    EXPECT_FALSE(store.Finish("job-2", proto::JOB_STATE_CANCELLED, "", 103.0));
    EXPECT_FALSE(store.Succeed("job-2", {}, 103.0));
    store.SetRunning("job-2", Progress("localize", 1, 2, 3));
    EXPECT_EQ(store.CountUnfinished(), 1u);
  }
  JobStore store(Db());
  const std::vector<proto::JobStatus> jobs = store.Jobs();
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].job_id(), "job-1");
  EXPECT_EQ(jobs[0].state(), proto::JOB_STATE_RUNNING);
  EXPECT_EQ(jobs[0].phase(), "localize");
  EXPECT_EQ(jobs[0].done(), 5u);
  EXPECT_EQ(jobs[0].total(), 40u);
  EXPECT_EQ(jobs[0].evaluations(), 1234u);
  EXPECT_FALSE(jobs[0].has_step());
  EXPECT_EQ(jobs[0].submitted_unix_s(), 100.0);
  EXPECT_EQ(jobs[1].state(), proto::JOB_STATE_FAILED);
  EXPECT_EQ(jobs[1].error(), "scan 3: no map");
  EXPECT_EQ(store.Spec("job-2")->seed(), 2u);
  EXPECT_EQ(store.Unfinished(), std::vector<std::string>{"job-1"});
  EXPECT_EQ(store.AddJob(LocalizeSpec(3), 103.0), "job-3");  // ids are never reused
}

// What a client reads of a running job (its step too) is what it read before a restart; a step
// that ends is gone.
TEST_F(JobStoreTest, AJobsStepIsKeptUntilItEnds) {
  proto::JobStatus searching = Progress("slam", 450, 910, 77);
  searching.mutable_step()->set_name("global search");
  searching.mutable_step()->set_done(30);
  searching.mutable_step()->set_total(100);
  {
    JobStore store(Db());
    store.SetRunning(store.AddJob(LocalizeSpec(1), 1.0), searching);
  }
  JobStore store(Db());
  proto::JobStatus read = *store.Status("job-1");
  EXPECT_EQ(read.phase(), "slam");
  EXPECT_EQ(read.done(), 450u);
  ASSERT_TRUE(read.has_step());
  EXPECT_EQ(read.step().name(), "global search");
  EXPECT_EQ(read.step().done(), 30u);
  EXPECT_EQ(read.step().total(), 100u);
  store.SetRunning("job-1", Progress("slam", 451, 910, 80));
  read = *store.Status("job-1");
  EXPECT_EQ(read.done(), 451u);
  EXPECT_FALSE(read.has_step());
}

// A database of schema version 1 (no step) opens as version 2, its jobs without a step.
TEST_F(JobStoreTest, AVersion1DatabaseGainsTheStep) {
  {
    Database v1(Db());
    v1.Execute(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value INTEGER NOT NULL);"
        "CREATE TABLE jobs (id INTEGER PRIMARY KEY AUTOINCREMENT,"
        "  kind INTEGER NOT NULL, spec BLOB NOT NULL, state INTEGER NOT NULL,"
        "  phase TEXT NOT NULL DEFAULT '', done INTEGER NOT NULL DEFAULT 0,"
        "  total INTEGER NOT NULL DEFAULT 0, evaluations INTEGER NOT NULL DEFAULT 0,"
        "  error TEXT NOT NULL DEFAULT '', submitted REAL NOT NULL, finished REAL NOT NULL"
        "  DEFAULT 0);"
        "INSERT INTO meta VALUES ('schema', 1);"
        "INSERT INTO jobs (kind, spec, state, phase, done, total, submitted)"
        "  VALUES (1, x'', 2, 'localize', 5, 40, 100.0);");
  }
  {
    JobStore store(Db());
    const proto::JobStatus read = *store.Status("job-1");
    EXPECT_EQ(read.phase(), "localize");
    EXPECT_EQ(read.done(), 5u);
    EXPECT_FALSE(read.has_step());
    proto::JobStatus searching = Progress("slam", 6, 40, 0);
    searching.mutable_step()->set_name("global search");
    store.SetRunning("job-1", searching);
  }
  JobStore store(Db());  // now version 2
  EXPECT_EQ(store.Status("job-1")->step().name(), "global search");
  Database db(Db());
  Statement schema = db.Prepare("SELECT value FROM meta WHERE key = 'schema'");
  ASSERT_TRUE(schema.Step());
  EXPECT_EQ(schema.Int(0), 2);
}

TEST_F(JobStoreTest, UnknownAndMalformedJobIdsFindNothing) {
  JobStore store(Db());
  store.AddJob(LocalizeSpec(1), 1.0);
  for (const char* id : {"job-2", "job-0", "job-", "job-1x", "1", "'; DROP TABLE jobs; --", ""}) {
    EXPECT_FALSE(store.Status(id)) << id;
    EXPECT_FALSE(store.Spec(id)) << id;
  }
  EXPECT_TRUE(store.Status("job-1"));
}

TEST_F(JobStoreTest, EachIslandKeepsItsLatestCheckpoint) {
  JobStore store(Db());
  const std::string job = store.AddJob(LocalizeSpec(1), 1.0);
  store.SaveCheckpoint(job, 0, 1, "island 0 epoch 1");
  store.SaveCheckpoint(job, 1, 1, std::string("island 1\0epoch 1", 16));
  store.SaveCheckpoint(job, 0, 2, "island 0 epoch 2");
  const auto checkpoints = store.Checkpoints(job);
  ASSERT_EQ(checkpoints.size(), 2u);
  EXPECT_EQ(checkpoints[0].epoch, 2u);
  EXPECT_EQ(checkpoints[0].bytes, "island 0 epoch 2");
  EXPECT_EQ(checkpoints[1].bytes, std::string("island 1\0epoch 1", 16));  // binary-safe
  EXPECT_TRUE(store.Checkpoints(store.AddJob(LocalizeSpec(2), 2.0)).empty());
  // A job that ends keeps no checkpoint: it is never resumed.
  EXPECT_TRUE(store.Finish(job, proto::JOB_STATE_CANCELLED, "", 3.0));
  EXPECT_TRUE(store.Checkpoints(job).empty());
}

TEST_F(JobStoreTest, DatasetsAndResultsRoundTrip) {
  JobStore store(Db());
  const std::string content("CARMEN\0log", 10);
  EXPECT_TRUE(store.PutDataset(std::string(64, 'c'), "intel.clf", content));
  EXPECT_FALSE(store.PutDataset(std::string(64, 'c'), "intel.clf", content));
  EXPECT_TRUE(store.HasDataset(std::string(64, 'c')));
  EXPECT_EQ(store.Dataset(std::string(64, 'c')), content);
  EXPECT_FALSE(store.Dataset(std::string(64, 'd')));

  const std::string job = store.AddJob(LocalizeSpec(1), 1.0);
  proto::ResultFile trajectory, report;
  trajectory.set_name("trajectory.txt");
  trajectory.set_content("0 0 0 0\n");
  report.set_name("report.json");
  report.set_content("{}");
  EXPECT_TRUE(store.Succeed(job, {trajectory, report}, 2.0));
  const auto files = store.Result(job);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].name(), "report.json");
  EXPECT_EQ(files[1].content(), "0 0 0 0\n");
  EXPECT_TRUE(store.Unfinished().empty());
}

// What kill -9 leaves behind: a process that committed and died without closing anything.
TEST_F(JobStoreTest, CommittedWorkSurvivesKillMinus9) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    JobStore store(Db());
    const std::string job = store.AddJob(LocalizeSpec(7), 1.0);
    store.SetRunning(job, Progress("islands", 3, 10, 999));
    store.SaveCheckpoint(job, 2, 3, "epoch 3");
    raise(SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_EQ(WTERMSIG(status), SIGKILL);

  JobStore store(Db());
  EXPECT_EQ(store.Unfinished(), std::vector<std::string>{"job-1"});
  EXPECT_EQ(store.Spec("job-1")->seed(), 7u);
  EXPECT_EQ(store.Status("job-1")->done(), 3u);
  const auto checkpoints = store.Checkpoints("job-1");
  ASSERT_EQ(checkpoints.size(), 1u);
  EXPECT_EQ(checkpoints[0].bytes, "epoch 3");
}

TEST_F(JobStoreTest, AFileThatIsNotADatabaseIsAClearError) {
  std::ofstream(Db()) << "this is not an SQLite database, just text long enough to be checked";
  try {
    JobStore store(Db());
    FAIL() << "opened a text file as a database";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(Db().string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace evoslam
