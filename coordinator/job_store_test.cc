#include "coordinator/job_store.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <map>
#include <set>

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
  std::string job1, job2;
  {
    JobStore store(Db());
    job1 = store.AddJob(LocalizeSpec(1), "", 100.0);
    job2 = store.AddJob(LocalizeSpec(2), "", 101.0);
    store.SetRunning(job1, Progress("localize", 5, 40, 1234));
    EXPECT_TRUE(store.Finish(job2, proto::JOB_STATE_FAILED, "scan 3: no map", 102.0));
    // A job ends once: neither a later success nor progress overrides how it ended.
    EXPECT_FALSE(store.Finish(job2, proto::JOB_STATE_CANCELLED, "", 103.0));
    EXPECT_FALSE(store.Succeed(job2, {}, 103.0));
    store.SetRunning(job2, Progress("localize", 1, 2, 3));
    EXPECT_EQ(store.CountUnfinished(), 1u);
  }
  JobStore store(Db());
  const std::vector<proto::JobStatus> jobs = store.Jobs();
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].job_id(), job1);
  EXPECT_EQ(jobs[0].state(), proto::JOB_STATE_RUNNING);
  EXPECT_EQ(jobs[0].phase(), "localize");
  EXPECT_EQ(jobs[0].done(), 5u);
  EXPECT_EQ(jobs[0].total(), 40u);
  EXPECT_EQ(jobs[0].evaluations(), 1234u);
  EXPECT_FALSE(jobs[0].has_step());
  EXPECT_EQ(jobs[0].submitted_unix_s(), 100.0);
  EXPECT_EQ(jobs[1].state(), proto::JOB_STATE_FAILED);
  EXPECT_EQ(jobs[1].error(), "scan 3: no map");
  EXPECT_EQ(store.Spec(job2)->seed(), 2u);
  EXPECT_EQ(store.Unfinished(), std::vector<std::string>{job1});
}

// Job ids are random: nobody can guess another's job, and none is ever given twice.
TEST_F(JobStoreTest, JobIdsAreRandomAndReadable) {
  JobStore store(Db());
  std::set<std::string> ids;
  for (int i = 0; i < 200; ++i) {
    const std::string id = store.AddJob(LocalizeSpec(1), "", 1.0);
    ASSERT_EQ(id.size(), 4u + 32u) << id;
    EXPECT_EQ(id.substr(0, 4), "job-");
    EXPECT_EQ(id.find_first_not_of("0123456789abcdef", 4), std::string::npos) << id;
    EXPECT_TRUE(ids.insert(id).second) << id;
  }
}

// A job belongs to the key that submitted it; a listing for that key shows its jobs alone.
TEST_F(JobStoreTest, JobsAndDatasetsBelongToTheirOwner) {
  JobStore store(Db());
  const std::string alice = store.AddJob(LocalizeSpec(1), "alice-key", 1.0);
  const std::string bob = store.AddJob(LocalizeSpec(2), "bob-key", 2.0);
  EXPECT_EQ(store.Owner(alice), "alice-key");
  EXPECT_EQ(store.Owner(bob), "bob-key");
  EXPECT_FALSE(store.Owner("job-nobody"));
  ASSERT_EQ(store.Jobs("alice-key").size(), 1u);
  EXPECT_EQ(store.Jobs("alice-key")[0].job_id(), alice);
  EXPECT_TRUE(store.Jobs("carol-key").empty());
  EXPECT_EQ(store.Jobs().size(), 2u);

  const std::string sha(64, 'c');
  EXPECT_TRUE(store.PutDataset(sha, "intel.clf", "12345", "alice-key", 1.0));
  EXPECT_TRUE(store.OwnsDataset(sha, "alice-key"));
  EXPECT_FALSE(store.OwnsDataset(sha, "bob-key"));
  EXPECT_FALSE(store.ClaimDataset(sha, "bob-key", 2.0)) << "only the bytes prove possession";
  EXPECT_FALSE(store.PutDataset(sha, "mine.clf", "12345", "bob-key", 2.0));  // stored once
  EXPECT_TRUE(store.OwnsDataset(sha, "bob-key"));
  EXPECT_EQ(store.StoredBytes("alice-key"), 5u);
  EXPECT_EQ(store.StoredBytes("bob-key"), 5u);
  proto::ResultFile report;
  report.set_name("report.json");
  report.set_content("{}");
  EXPECT_TRUE(store.Succeed(bob, {report}, 3.0));
  EXPECT_EQ(store.StoredBytes("bob-key"), 7u);
  EXPECT_EQ(store.StoredBytes("carol-key"), 0u);
}

// Ended jobs go once the retention has passed, and with them what they alone read; a dataset a
// job still reads, or uploaded within the retention, stays.
TEST_F(JobStoreTest, CollectDropsWhatOutlivedTheRetention) {
  JobStore store(Db());
  const std::string log(64, 'a'), map(64, 'e'), fresh(64, 'c'), unused(64, 'd');
  for (const std::string& sha : {log, map, unused}) store.PutDataset(sha, "x", "bytes", "k", 10.0);
  store.PutDataset(fresh, "x", "bytes", "k", 95.0);
  proto::JobSpec reads_log = LocalizeSpec(1);
  reads_log.mutable_log()->set_sha256(log);
  proto::JobSpec reads_map = LocalizeSpec(2);
  reads_map.mutable_log()->set_sha256(map);
  const std::string running = store.AddJob(reads_log, "k", 10.0);
  const std::string ended = store.AddJob(reads_map, "k", 10.0);
  const std::string recent = store.AddJob(LocalizeSpec(3), "k", 10.0);
  EXPECT_TRUE(store.Succeed(ended, {}, 20.0));
  EXPECT_TRUE(store.Finish(recent, proto::JOB_STATE_FAILED, "x", 95.0));
  store.SetRunning(running, Progress("localize", 1, 2, 3));

  const JobStore::Collected collected = store.Collect(100.0, 50.0);
  EXPECT_EQ(collected.jobs, 1u);
  EXPECT_EQ(collected.datasets, 2u);  // map (its job went) and unused
  EXPECT_FALSE(store.Status(ended));
  EXPECT_TRUE(store.Status(running));
  EXPECT_TRUE(store.Status(recent));
  EXPECT_TRUE(store.HasDataset(log));
  EXPECT_TRUE(store.HasDataset(fresh));
  EXPECT_FALSE(store.HasDataset(map));
  EXPECT_FALSE(store.HasDataset(unused));
  EXPECT_EQ(store.Collect(100.0, 50.0).datasets, 0u);
}

// What a client reads of a running job (its step too) is what it read before a restart; a step
// that ends is gone.
TEST_F(JobStoreTest, AJobsStepIsKeptUntilItEnds) {
  proto::JobStatus searching = Progress("slam", 450, 910, 77);
  searching.mutable_step()->set_name("global search");
  searching.mutable_step()->set_done(30);
  searching.mutable_step()->set_total(100);
  std::string job;
  {
    JobStore store(Db());
    job = store.AddJob(LocalizeSpec(1), "", 1.0);
    store.SetRunning(job, searching);
  }
  JobStore store(Db());
  proto::JobStatus read = *store.Status(job);
  EXPECT_EQ(read.phase(), "slam");
  EXPECT_EQ(read.done(), 450u);
  ASSERT_TRUE(read.has_step());
  EXPECT_EQ(read.step().name(), "global search");
  EXPECT_EQ(read.step().done(), 30u);
  EXPECT_EQ(read.step().total(), 100u);
  store.SetRunning(job, Progress("slam", 451, 910, 80));
  read = *store.Status(job);
  EXPECT_EQ(read.done(), 451u);
  EXPECT_FALSE(read.has_step());
}

// A database of schema version 1 (no step) opens as the current version, its jobs without a step,
// keeping their ids, and owned by "", the owner of every client without CURVE.
TEST_F(JobStoreTest, AVersion1DatabaseGainsTheStepAndOwners) {
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
        "  VALUES (1, x'', 2, 'localize', 5, 40, 100.0);"
        "CREATE TABLE datasets (sha256 TEXT PRIMARY KEY, name TEXT NOT NULL,"
        "  content BLOB NOT NULL);"
        "INSERT INTO datasets VALUES ('" +
        std::string(64, 'e') + "', 'old.clf', x'0102');");
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
  JobStore store(Db());  // now the current version
  EXPECT_EQ(store.Status("job-1")->step().name(), "global search");
  EXPECT_EQ(store.Owner("job-1"), "");
  EXPECT_TRUE(store.OwnsDataset(std::string(64, 'e'), ""));
  EXPECT_EQ(store.StoredBytes(""), 2u);
  Database db(Db());
  Statement schema = db.Prepare("SELECT value FROM meta WHERE key = 'schema'");
  ASSERT_TRUE(schema.Step());
  EXPECT_EQ(schema.Int(0), 4);
}

// A database of schema version 3 (jobs without submit ids) opens as version 4: its jobs are as
// they were, no retried submit finds them, and new jobs are found by their submit ids.
TEST_F(JobStoreTest, AVersion3DatabaseGainsSubmitIds) {
  const std::string old_job = "job-" + std::string(32, '3');
  {
    Database v3(Db());
    v3.Execute(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value INTEGER NOT NULL);"
        "CREATE TABLE datasets (sha256 TEXT PRIMARY KEY, name TEXT NOT NULL,"
        "  content BLOB NOT NULL);"
        "CREATE TABLE jobs (id INTEGER PRIMARY KEY AUTOINCREMENT,"
        "  kind INTEGER NOT NULL, spec BLOB NOT NULL, state INTEGER NOT NULL,"
        "  phase TEXT NOT NULL DEFAULT '', done INTEGER NOT NULL DEFAULT 0,"
        "  total INTEGER NOT NULL DEFAULT 0, evaluations INTEGER NOT NULL DEFAULT 0,"
        "  error TEXT NOT NULL DEFAULT '', submitted REAL NOT NULL, finished REAL NOT NULL"
        "  DEFAULT 0, step BLOB NOT NULL DEFAULT x'', public_id TEXT NOT NULL DEFAULT '',"
        "  owner TEXT NOT NULL DEFAULT '');"
        "CREATE TABLE dataset_owners (sha256 TEXT NOT NULL, owner TEXT NOT NULL,"
        "  size INTEGER NOT NULL, uploaded REAL NOT NULL, PRIMARY KEY (sha256, owner));"
        "CREATE TABLE checkpoints (job INTEGER NOT NULL REFERENCES jobs(id),"
        "  island INTEGER NOT NULL, epoch INTEGER NOT NULL, state BLOB NOT NULL,"
        "  PRIMARY KEY (job, island));"
        "CREATE TABLE results (job INTEGER NOT NULL REFERENCES jobs(id),"
        "  name TEXT NOT NULL, content BLOB NOT NULL, PRIMARY KEY (job, name));"
        "CREATE UNIQUE INDEX jobs_by_public_id ON jobs (public_id);"
        "INSERT INTO meta VALUES ('schema', 3);"
        "INSERT INTO jobs (kind, spec, state, phase, done, total, submitted, public_id, owner)"
        "  VALUES (1, x'', 1, '', 0, 0, 100.0, '" +
        old_job + "', 'alice-key');");
  }
  {
    JobStore store(Db());
    EXPECT_EQ(store.Status(old_job)->state(), proto::JOB_STATE_QUEUED);
    EXPECT_EQ(store.Owner(old_job), "alice-key");
    EXPECT_FALSE(store.FindSubmit("alice-key", ""));
    const std::string job = store.AddJob(LocalizeSpec(1), "alice-key", 101.0, {"s-1", "hash"});
    EXPECT_EQ(store.FindSubmit("alice-key", "s-1")->job_id, job);
    EXPECT_EQ(store.Unfinished(), (std::vector<std::string>{old_job, job}));
  }
  JobStore store(Db());  // reopened: nothing to migrate any more
  EXPECT_EQ(store.Jobs().size(), 2u);
  Database db(Db());
  Statement schema = db.Prepare("SELECT value FROM meta WHERE key = 'schema'");
  ASSERT_TRUE(schema.Step());
  EXPECT_EQ(schema.Int(0), 4);
}

// A database a newer build wrote is refused, not misread.
TEST_F(JobStoreTest, ANewerSchemaIsAClearError) {
  {
    Database newer(Db());
    newer.Execute(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value INTEGER NOT NULL);"
        "INSERT INTO meta VALUES ('schema', 99);");
  }
  try {
    JobStore store(Db());
    FAIL() << "opened a database of schema 99";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has schema version 99, this build reads version 4"),
              std::string::npos)
        << e.what();
  }
}

// A submit id names one job of its owner, whose spec's hash is kept with it; another owner's
// same id is another job, and jobs submitted without an id are never found by one.
TEST_F(JobStoreTest, ASubmitIdNamesOneJobOfItsOwner) {
  JobStore store(Db());
  const std::string alice = store.AddJob(LocalizeSpec(1), "alice-key", 1.0, {"s-1", "hash-a"});
  const std::string bob = store.AddJob(LocalizeSpec(1), "bob-key", 1.0, {"s-1", "hash-b"});
  EXPECT_NE(alice, bob);
  const auto found = store.FindSubmit("alice-key", "s-1");
  ASSERT_TRUE(found);
  EXPECT_EQ(found->job_id, alice);
  EXPECT_EQ(found->spec_sha256, "hash-a");
  EXPECT_EQ(store.FindSubmit("bob-key", "s-1")->job_id, bob);
  EXPECT_FALSE(store.FindSubmit("carol-key", "s-1"));
  EXPECT_FALSE(store.FindSubmit("alice-key", "s-2"));
  // The store itself never makes a second job under one id.
  EXPECT_THROW(store.AddJob(LocalizeSpec(2), "alice-key", 2.0, {"s-1", "hash-c"}), Error);
  EXPECT_EQ(store.Jobs("alice-key").size(), 1u);
  // Without ids, as many jobs as are submitted.
  store.AddJob(LocalizeSpec(3), "alice-key", 3.0);
  store.AddJob(LocalizeSpec(3), "alice-key", 3.0);
  EXPECT_EQ(store.Jobs("alice-key").size(), 3u);
  EXPECT_FALSE(store.FindSubmit("alice-key", ""));
}

// A job dropped after the retention takes its submit id with it: the id may name a new job.
TEST_F(JobStoreTest, CollectingAJobDropsItsSubmitId) {
  JobStore store(Db());
  const std::string old = store.AddJob(LocalizeSpec(1), "k", 1.0, {"s-1", "hash"});
  EXPECT_TRUE(store.Finish(old, proto::JOB_STATE_CANCELLED, "", 2.0));
  EXPECT_EQ(store.Collect(100.0, 50.0).jobs, 1u);
  EXPECT_FALSE(store.FindSubmit("k", "s-1"));
  const std::string again = store.AddJob(LocalizeSpec(1), "k", 100.0, {"s-1", "hash"});
  EXPECT_NE(again, old);
  EXPECT_EQ(store.FindSubmit("k", "s-1")->job_id, again);
}

// What the metrics report: jobs by state, and the bytes kept, a dataset two owners hold once.
TEST_F(JobStoreTest, CountsJobsByStateAndTheBytesKept) {
  JobStore store(Db());
  EXPECT_EQ(store.CountTotals(), JobStore::Totals{});
  const std::string a = store.AddJob(LocalizeSpec(1), "", 1.0);
  const std::string b = store.AddJob(LocalizeSpec(2), "", 1.0);
  store.AddJob(LocalizeSpec(3), "", 1.0);
  store.SetRunning(a, Progress("localize", 1, 2, 3));
  proto::ResultFile report;
  report.set_name("report.json");
  report.set_content("{\"ok\": 1}");
  EXPECT_TRUE(store.Succeed(b, {report}, 2.0));
  const std::map<proto::JobState, std::uint64_t> by_state = {
      {proto::JOB_STATE_QUEUED, 1}, {proto::JOB_STATE_RUNNING, 1}, {proto::JOB_STATE_SUCCEEDED, 1}};
  EXPECT_EQ(store.CountTotals(), (JobStore::Totals{.jobs = by_state, .stored_bytes = 9}));
  store.PutDataset(std::string(64, 'c'), "log.clf", "12345", "alice", 1.0);
  store.PutDataset(std::string(64, 'c'), "log.clf", "12345", "bob", 1.0);
  EXPECT_EQ(store.CountTotals(), (JobStore::Totals{.jobs = by_state, .stored_bytes = 5 + 9}));
}

TEST_F(JobStoreTest, UnknownAndMalformedJobIdsFindNothing) {
  JobStore store(Db());
  const std::string job = store.AddJob(LocalizeSpec(1), "", 1.0);
  for (const std::string& id : {std::string("job-1"), std::string("job-0"), std::string("job-"),
                                job + "x", job.substr(0, 20), std::string("1"),
                                std::string("'; DROP TABLE jobs; --"), std::string()}) {
    EXPECT_FALSE(store.Status(id)) << id;
    EXPECT_FALSE(store.Spec(id)) << id;
  }
  EXPECT_TRUE(store.Status(job));
}

TEST_F(JobStoreTest, EachIslandKeepsItsLatestCheckpoint) {
  JobStore store(Db());
  const std::string job = store.AddJob(LocalizeSpec(1), "", 1.0);
  store.SaveCheckpoint(job, 0, 1, "island 0 epoch 1");
  store.SaveCheckpoint(job, 1, 1, std::string("island 1\0epoch 1", 16));
  store.SaveCheckpoint(job, 0, 2, "island 0 epoch 2");
  const auto checkpoints = store.Checkpoints(job);
  ASSERT_EQ(checkpoints.size(), 2u);
  EXPECT_EQ(checkpoints[0].epoch, 2u);
  EXPECT_EQ(checkpoints[0].bytes, "island 0 epoch 2");
  EXPECT_EQ(checkpoints[1].bytes, std::string("island 1\0epoch 1", 16));  // binary-safe
  EXPECT_TRUE(store.Checkpoints(store.AddJob(LocalizeSpec(2), "", 2.0)).empty());
  // A job that ends keeps no checkpoint: it is never resumed.
  EXPECT_TRUE(store.Finish(job, proto::JOB_STATE_CANCELLED, "", 3.0));
  EXPECT_TRUE(store.Checkpoints(job).empty());
}

TEST_F(JobStoreTest, DatasetsAndResultsRoundTrip) {
  JobStore store(Db());
  const std::string content("CARMEN\0log", 10);
  EXPECT_TRUE(store.PutDataset(std::string(64, 'c'), "intel.clf", content, "", 1.0));
  EXPECT_FALSE(store.PutDataset(std::string(64, 'c'), "intel.clf", content, "", 1.0));
  EXPECT_TRUE(store.HasDataset(std::string(64, 'c')));
  EXPECT_EQ(store.Dataset(std::string(64, 'c')), content);
  EXPECT_FALSE(store.Dataset(std::string(64, 'd')));

  const std::string job = store.AddJob(LocalizeSpec(1), "", 1.0);
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

// A large dataset goes in piece by piece, each piece read only when it is written.
TEST_F(JobStoreTest, ADatasetStoredInPiecesIsReadBackWhole) {
  JobStore store(Db());
  std::string content(100000, '\0');
  for (std::size_t i = 0; i < content.size(); ++i) content[i] = static_cast<char>(i * 7 % 251);
  std::size_t at = 0, largest = 0;
  const JobStore::ReadBytes read = [&](std::span<char> piece) {
    largest = std::max(largest, piece.size());
    std::copy_n(content.data() + at, piece.size(), piece.data());
    at += piece.size();
  };
  const std::string sha(64, 'c');
  EXPECT_TRUE(store.PutDataset(sha, "big.clf", content.size(), read, 4096, "alice", 1.0));
  EXPECT_EQ(at, content.size());
  EXPECT_EQ(largest, 4096u);
  EXPECT_EQ(store.Dataset(sha), content);
  EXPECT_EQ(store.StoredBytes("alice"), content.size());
  // Stored once: the second owner's bytes are not read at all.
  at = 0;
  EXPECT_FALSE(store.PutDataset(sha, "big.clf", content.size(), read, 4096, "bob", 2.0));
  EXPECT_EQ(at, 0u);
  EXPECT_TRUE(store.OwnsDataset(sha, "bob"));
}

// A store whose bytes cannot be read to the end leaves nothing: no row anybody could find, and no
// owner.
TEST_F(JobStoreTest, AStoreCutShortLeavesNothing) {
  JobStore store(Db());
  std::size_t pieces = 0;
  const JobStore::ReadBytes failing = [&](std::span<char> piece) {
    if (++pieces == 3) throw Error("the spool went");
    std::fill(piece.begin(), piece.end(), 'x');
  };
  const std::string sha(64, 'd');
  EXPECT_THROW(store.PutDataset(sha, "cut.clf", 10000, failing, 1000, "alice", 1.0), Error);
  EXPECT_FALSE(store.HasDataset(sha));
  EXPECT_FALSE(store.OwnsDataset(sha, "alice"));
  EXPECT_EQ(store.StoredBytes("alice"), 0u);
}

// What a crash in the middle of a store leaves: bytes nobody holds. They are dropped at the next
// start, and a collection in the meantime leaves them alone (they may be a store under way).
TEST_F(JobStoreTest, BytesNobodyHoldsAreDroppedAtStartOnly) {
  const std::string partial(64, 'a'), held(64, 'b'), read(64, 'c');
  {
    JobStore store(Db());
    store.PutDataset(held, "held.clf", "held bytes", "alice", 1.0);
    store.PutDataset(read, "read.clf", "read bytes", "alice", 1.0);
    proto::JobSpec spec = LocalizeSpec(1);
    spec.mutable_log()->set_sha256(read);
    store.AddJob(spec, "bob", 1.0);
  }
  {
    // A crashed store: the row went in, the owner never did.
    Database db(Db());
    db.Prepare("INSERT INTO datasets (sha256, name, content) VALUES (?1, 'p', zeroblob(10))")
        .Bind(1, partial)
        .Run();
    db.Prepare("DELETE FROM dataset_owners WHERE sha256 = ?1").Bind(1, read).Run();
  }
  JobStore store(Db());
  EXPECT_EQ(store.Collect(100.0, 1000.0).datasets, 0u);
  EXPECT_TRUE(store.HasDataset(partial)) << "a collection dropped a store under way";
  EXPECT_EQ(store.DropUnheldDatasets(), 1u);
  EXPECT_FALSE(store.HasDataset(partial));
  EXPECT_TRUE(store.HasDataset(held));
  EXPECT_TRUE(store.HasDataset(read)) << "a job reads it";
}

// What kill -9 leaves behind: a process that committed and died without closing anything.
TEST_F(JobStoreTest, CommittedWorkSurvivesKillMinus9) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    JobStore store(Db());
    const std::string job = store.AddJob(LocalizeSpec(7), "", 1.0);
    std::ofstream(Db().string() + ".id") << job;
    store.SetRunning(job, Progress("islands", 3, 10, 999));
    store.SaveCheckpoint(job, 2, 3, "epoch 3");
    raise(SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_EQ(WTERMSIG(status), SIGKILL);

  JobStore store(Db());
  std::string job;
  std::ifstream(Db().string() + ".id") >> job;
  EXPECT_EQ(store.Unfinished(), std::vector<std::string>{job});
  EXPECT_EQ(store.Spec(job)->seed(), 7u);
  EXPECT_EQ(store.Status(job)->done(), 3u);
  const auto checkpoints = store.Checkpoints(job);
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
