#include "coordinator/job_store.h"

#include <charconv>

#include "common/util/error.h"

namespace evoslam {
namespace {

// 2: jobs.step, the step under way inside a running job (a serialised JobStep; empty: none).
constexpr std::int64_t kSchemaVersion = 2;

proto::JobStatus StatusFrom(Statement& row) {
  proto::JobStatus s;
  s.set_job_id("job-" + std::to_string(row.Int(0)));
  s.set_kind(static_cast<proto::JobKind>(row.Int(1)));
  s.set_state(static_cast<proto::JobState>(row.Int(2)));
  s.set_phase(row.Text(3));
  s.set_done(static_cast<std::uint64_t>(row.Int(4)));
  s.set_total(static_cast<std::uint64_t>(row.Int(5)));
  s.set_evaluations(static_cast<std::uint64_t>(row.Int(6)));
  s.set_error(row.Text(7));
  s.set_submitted_unix_s(row.Real(8));
  s.set_finished_unix_s(row.Real(9));
  const std::string step = row.Text(10);
  if (!step.empty() && !s.mutable_step()->ParseFromString(step)) {
    throw Error("database: the progress of " + s.job_id() + " is corrupt");
  }
  return s;
}

constexpr const char* kStatusColumns =
    "id, kind, state, phase, done, total, evaluations, error, submitted, finished, step";

}  // namespace

JobStore::JobStore(const std::filesystem::path& path) : db_(path) {
  db_.Transaction([&] {
    db_.Execute(
        "CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value INTEGER NOT NULL);"
        "CREATE TABLE IF NOT EXISTS datasets (sha256 TEXT PRIMARY KEY, name TEXT NOT NULL,"
        "  content BLOB NOT NULL);"
        "CREATE TABLE IF NOT EXISTS jobs (id INTEGER PRIMARY KEY AUTOINCREMENT,"
        "  kind INTEGER NOT NULL, spec BLOB NOT NULL, state INTEGER NOT NULL,"
        "  phase TEXT NOT NULL DEFAULT '', done INTEGER NOT NULL DEFAULT 0,"
        "  total INTEGER NOT NULL DEFAULT 0, evaluations INTEGER NOT NULL DEFAULT 0,"
        "  error TEXT NOT NULL DEFAULT '', submitted REAL NOT NULL, finished REAL NOT NULL"
        "  DEFAULT 0, step BLOB NOT NULL DEFAULT x'');"
        "CREATE TABLE IF NOT EXISTS checkpoints (job INTEGER NOT NULL REFERENCES jobs(id),"
        "  island INTEGER NOT NULL, epoch INTEGER NOT NULL, state BLOB NOT NULL,"
        "  PRIMARY KEY (job, island));"
        "CREATE TABLE IF NOT EXISTS results (job INTEGER NOT NULL REFERENCES jobs(id),"
        "  name TEXT NOT NULL, content BLOB NOT NULL, PRIMARY KEY (job, name));"
        "INSERT OR IGNORE INTO meta VALUES ('schema', 2);");
    Statement schema = db_.Prepare("SELECT value FROM meta WHERE key = 'schema'");
    const std::int64_t version = schema.Step() ? schema.Int(0) : 0;
    if (version == 1) {
      // Version 1 lacks only the step: its jobs have none.
      db_.Execute(
          "ALTER TABLE jobs ADD COLUMN step BLOB NOT NULL DEFAULT x'';"
          "UPDATE meta SET value = 2 WHERE key = 'schema';");
    } else if (version != kSchemaVersion) {
      throw Error("database " + path.string() + " has schema version " + std::to_string(version) +
                  ", this build reads version " + std::to_string(kSchemaVersion));
    }
  });
}

std::int64_t JobStore::JobNumber(const std::string& job_id) const {
  std::int64_t number = 0;
  const char* first = job_id.data() + 4;
  const char* last = job_id.data() + job_id.size();
  if (job_id.size() < 5 || job_id.compare(0, 4, "job-") != 0 ||
      std::from_chars(first, last, number).ptr != last || number <= 0)
    return -1;
  return number;
}

bool JobStore::PutDataset(const std::string& sha256, const std::string& name,
                          const std::string& content) {
  if (HasDataset(sha256)) return false;
  Statement insert =
      db_.Prepare("INSERT INTO datasets (sha256, name, content) VALUES (?1, ?2, ?3)");
  insert.Bind(1, sha256).Bind(2, name).BindBlob(3, content).Run();
  return true;
}

bool JobStore::HasDataset(const std::string& sha256) {
  Statement q = db_.Prepare("SELECT 1 FROM datasets WHERE sha256 = ?1");
  q.Bind(1, sha256);
  return q.Step();
}

std::optional<std::string> JobStore::Dataset(const std::string& sha256) {
  Statement q = db_.Prepare("SELECT content FROM datasets WHERE sha256 = ?1");
  q.Bind(1, sha256);
  if (!q.Step()) return std::nullopt;
  return q.Text(0);
}

std::string JobStore::AddJob(const proto::JobSpec& spec, double now_unix_s) {
  Statement insert =
      db_.Prepare("INSERT INTO jobs (kind, spec, state, submitted) VALUES (?1, ?2, ?3, ?4)");
  insert.Bind(1, static_cast<std::int64_t>(spec.kind()))
      .BindBlob(2, spec.SerializeAsString())
      .Bind(3, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .Bind(4, now_unix_s)
      .Run();
  return "job-" + std::to_string(db_.LastInsertId());
}

std::optional<proto::JobSpec> JobStore::Spec(const std::string& job_id) {
  Statement q = db_.Prepare("SELECT spec FROM jobs WHERE id = ?1");
  q.Bind(1, JobNumber(job_id));
  if (!q.Step()) return std::nullopt;
  proto::JobSpec spec;
  if (!spec.ParseFromString(q.Text(0)))
    throw Error("database: the spec of " + job_id + " is corrupt");
  return spec;
}

std::optional<proto::JobStatus> JobStore::Status(const std::string& job_id) {
  Statement q = db_.Prepare(std::string("SELECT ") + kStatusColumns + " FROM jobs WHERE id = ?1");
  q.Bind(1, JobNumber(job_id));
  if (!q.Step()) return std::nullopt;
  return StatusFrom(q);
}

std::vector<proto::JobStatus> JobStore::Jobs() {
  Statement q = db_.Prepare(std::string("SELECT ") + kStatusColumns + " FROM jobs ORDER BY id");
  std::vector<proto::JobStatus> jobs;
  while (q.Step()) jobs.push_back(StatusFrom(q));
  return jobs;
}

std::vector<std::string> JobStore::Unfinished() {
  Statement q = db_.Prepare("SELECT id FROM jobs WHERE state IN (?1, ?2) ORDER BY id");
  q.Bind(1, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .Bind(2, static_cast<std::int64_t>(proto::JOB_STATE_RUNNING));
  std::vector<std::string> ids;
  while (q.Step()) ids.push_back("job-" + std::to_string(q.Int(0)));
  return ids;
}

void JobStore::SetRunning(const std::string& job_id, const proto::JobStatus& progress) {
  Statement update = db_.Prepare(
      "UPDATE jobs SET state = ?2, phase = ?3, done = ?4, total = ?5, evaluations = ?6,"
      " step = ?8 WHERE id = ?1 AND state IN (?7, ?2)");
  update.Bind(1, JobNumber(job_id))
      .Bind(2, static_cast<std::int64_t>(proto::JOB_STATE_RUNNING))
      .Bind(3, progress.phase())
      .Bind(4, static_cast<std::int64_t>(progress.done()))
      .Bind(5, static_cast<std::int64_t>(progress.total()))
      .Bind(6, static_cast<std::int64_t>(progress.evaluations()))
      .Bind(7, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .BindBlob(8, progress.has_step() ? progress.step().SerializeAsString() : std::string())
      .Run();
}

bool JobStore::Finish(const std::string& job_id, proto::JobState state, const std::string& error,
                      double now_unix_s) {
  Statement update = db_.Prepare(
      "UPDATE jobs SET state = ?2, error = ?3, finished = ?4 WHERE id = ?1 AND state IN (?5, ?6)");
  update.Bind(1, JobNumber(job_id))
      .Bind(2, static_cast<std::int64_t>(state))
      .Bind(3, error)
      .Bind(4, now_unix_s)
      .Bind(5, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .Bind(6, static_cast<std::int64_t>(proto::JOB_STATE_RUNNING))
      .Run();
  if (db_.Changes() == 0) return false;
  // A finished job is never resumed: its checkpoints would only take room.
  db_.Prepare("DELETE FROM checkpoints WHERE job = ?1").Bind(1, JobNumber(job_id)).Run();
  return true;
}

bool JobStore::Succeed(const std::string& job_id, const std::vector<proto::ResultFile>& files,
                       double now_unix_s) {
  bool finished = false;
  db_.Transaction([&] {
    finished = Finish(job_id, proto::JOB_STATE_SUCCEEDED, "", now_unix_s);
    if (finished) SaveResult(job_id, files);
  });
  return finished;
}

std::size_t JobStore::CountUnfinished() {
  Statement q = db_.Prepare("SELECT COUNT(*) FROM jobs WHERE state IN (?1, ?2)");
  q.Bind(1, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .Bind(2, static_cast<std::int64_t>(proto::JOB_STATE_RUNNING));
  q.Step();
  return static_cast<std::size_t>(q.Int(0));
}

void JobStore::SaveCheckpoint(const std::string& job_id, std::uint32_t island, std::uint64_t epoch,
                              const std::string& bytes) {
  Statement upsert = db_.Prepare(
      "INSERT INTO checkpoints (job, island, epoch, state) VALUES (?1, ?2, ?3, ?4)"
      " ON CONFLICT (job, island) DO UPDATE SET epoch = excluded.epoch, state = excluded.state");
  upsert.Bind(1, JobNumber(job_id))
      .Bind(2, static_cast<std::int64_t>(island))
      .Bind(3, static_cast<std::int64_t>(epoch))
      .BindBlob(4, bytes)
      .Run();
}

std::vector<JobStore::Checkpoint> JobStore::Checkpoints(const std::string& job_id) {
  Statement q =
      db_.Prepare("SELECT island, epoch, state FROM checkpoints WHERE job = ?1 ORDER BY island");
  q.Bind(1, JobNumber(job_id));
  std::vector<Checkpoint> out;
  while (q.Step()) {
    out.push_back(
        {static_cast<std::uint32_t>(q.Int(0)), static_cast<std::uint64_t>(q.Int(1)), q.Text(2)});
  }
  return out;
}

void JobStore::SaveResult(const std::string& job_id, const std::vector<proto::ResultFile>& files) {
  Statement insert =
      db_.Prepare("INSERT OR REPLACE INTO results (job, name, content) VALUES (?1, ?2, ?3)");
  for (const proto::ResultFile& f : files) {
    insert.Bind(1, JobNumber(job_id)).Bind(2, f.name()).BindBlob(3, f.content()).Run();
  }
}

std::vector<proto::ResultFile> JobStore::Result(const std::string& job_id) {
  Statement q = db_.Prepare("SELECT name, content FROM results WHERE job = ?1 ORDER BY name");
  q.Bind(1, JobNumber(job_id));
  std::vector<proto::ResultFile> files;
  while (q.Step()) {
    proto::ResultFile f;
    f.set_name(q.Text(0));
    f.set_content(q.Text(1));
    files.push_back(std::move(f));
  }
  return files;
}

}  // namespace evoslam
