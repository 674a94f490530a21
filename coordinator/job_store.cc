#include "coordinator/job_store.h"

#include <algorithm>
#include <set>
#include <utility>

#include "common/util/error.h"
#include "common/util/random_id.h"

namespace evoslam {
namespace {

// 2: jobs.step, the step under way inside a running job (a serialised JobStep; empty: none).
// 3: jobs.public_id (the id clients see) and jobs.owner; dataset_owners.
// 4: jobs.submit_id and jobs.submit_sha256, what a retried submit is recognised by.
constexpr std::int64_t kSchemaVersion = 4;

proto::JobStatus StatusFrom(Statement& row) {
  proto::JobStatus s;
  s.set_job_id(row.Text(0));
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
    "public_id, kind, state, phase, done, total, evaluations, error, submitted, finished, step";

constexpr const char* kFinishedStates = "(3, 4, 5)";  // SUCCEEDED, FAILED, CANCELLED
static_assert(proto::JOB_STATE_SUCCEEDED == 3 && proto::JOB_STATE_FAILED == 4 &&
              proto::JOB_STATE_CANCELLED == 5);

// 128 bits from the system's CSPRNG: a job id tells nothing of another's.
std::string NewJobId() { return "job-" + RandomHexId(16); }

// The hashes of the datasets a job's spec reads.
std::vector<std::string> SpecDatasets(const proto::JobSpec& spec) {
  std::vector<std::string> hashes;
  for (const proto::DatasetRef* ref :
       {&spec.log(), &spec.map(), &spec.map_image(), &spec.relations()}) {
    if (!ref->sha256().empty()) hashes.push_back(ref->sha256());
  }
  return hashes;
}

// The most a transaction of a dataset's store writes after the first: big enough that the blob's
// overflow pages, which each opening of the blob walks from its start, are walked a few times
// only, and small enough that other writers get the database between two transactions.
constexpr std::uint64_t kBytesPerTransaction = std::uint64_t{32} << 20;

// A connection's PRAGMA synchronous for a scope; FULL again after it.
class Synchronous {
 public:
  Synchronous(Database& db, const char* level) : db_(db) {
    db_.Execute(std::string("PRAGMA synchronous = ") + level);
  }
  ~Synchronous() {
    try {
      db_.Execute("PRAGMA synchronous = FULL");
    } catch (const std::exception&) {
      // Setting a pragma touches no file; nothing to do if even that fails.
    }
  }
  Synchronous(const Synchronous&) = delete;
  Synchronous& operator=(const Synchronous&) = delete;

 private:
  Database& db_;
};

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
        "  DEFAULT 0, step BLOB NOT NULL DEFAULT x'', public_id TEXT NOT NULL DEFAULT '',"
        "  owner TEXT NOT NULL DEFAULT '', submit_id TEXT NOT NULL DEFAULT '',"
        "  submit_sha256 TEXT NOT NULL DEFAULT '');"
        "CREATE TABLE IF NOT EXISTS dataset_owners (sha256 TEXT NOT NULL, owner TEXT NOT NULL,"
        "  size INTEGER NOT NULL, uploaded REAL NOT NULL, PRIMARY KEY (sha256, owner));"
        "CREATE TABLE IF NOT EXISTS checkpoints (job INTEGER NOT NULL REFERENCES jobs(id),"
        "  island INTEGER NOT NULL, epoch INTEGER NOT NULL, state BLOB NOT NULL,"
        "  PRIMARY KEY (job, island));"
        "CREATE TABLE IF NOT EXISTS results (job INTEGER NOT NULL REFERENCES jobs(id),"
        "  name TEXT NOT NULL, content BLOB NOT NULL, PRIMARY KEY (job, name));"
        "INSERT OR IGNORE INTO meta VALUES ('schema', " +
        std::to_string(kSchemaVersion) + ");");
    Statement schema = db_.Prepare("SELECT value FROM meta WHERE key = 'schema'");
    std::int64_t version = schema.Step() ? schema.Int(0) : 0;
    if (version == 1) {
      // Version 1 lacks only the step: its jobs have none.
      db_.Execute(
          "ALTER TABLE jobs ADD COLUMN step BLOB NOT NULL DEFAULT x'';"
          "UPDATE meta SET value = 2 WHERE key = 'schema';");
      version = 2;
    }
    if (version == 2) {
      // Version 2's jobs keep the ids they were given; they and its datasets belong to "", the
      // owner of every client without CURVE.
      db_.Execute(
          "ALTER TABLE jobs ADD COLUMN public_id TEXT NOT NULL DEFAULT '';"
          "ALTER TABLE jobs ADD COLUMN owner TEXT NOT NULL DEFAULT '';"
          "UPDATE jobs SET public_id = 'job-' || id;"
          "INSERT OR IGNORE INTO dataset_owners SELECT sha256, '', length(content), 0"
          "  FROM datasets;"
          "UPDATE meta SET value = 3 WHERE key = 'schema';");
      version = 3;
    }
    if (version == 3) {
      // Version 3's jobs were submitted without an id: no retried submit finds them.
      db_.Execute(
          "ALTER TABLE jobs ADD COLUMN submit_id TEXT NOT NULL DEFAULT '';"
          "ALTER TABLE jobs ADD COLUMN submit_sha256 TEXT NOT NULL DEFAULT '';"
          "UPDATE meta SET value = 4 WHERE key = 'schema';");
      version = 4;
    }
    if (version != kSchemaVersion) {
      throw Error("database " + path.string() + " has schema version " + std::to_string(version) +
                  ", this build reads version " + std::to_string(kSchemaVersion));
    }
    // A submit id names one job of its owner; jobs submitted without one are not indexed.
    db_.Execute(
        "CREATE UNIQUE INDEX IF NOT EXISTS jobs_by_public_id ON jobs (public_id);"
        "CREATE UNIQUE INDEX IF NOT EXISTS jobs_by_submit_id ON jobs (owner, submit_id)"
        "  WHERE submit_id != '';");
  });
}

std::int64_t JobStore::JobNumber(const std::string& job_id) {
  if (job_id.empty()) return -1;
  Statement q = db_.Prepare("SELECT id FROM jobs WHERE public_id = ?1");
  q.Bind(1, job_id);
  return q.Step() ? q.Int(0) : -1;
}

bool JobStore::PutDataset(const std::string& sha256, const std::string& name,
                          const std::string& content, const std::string& owner, double now_unix_s) {
  std::size_t at = 0;
  const ReadBytes read = [&](std::span<char> piece) {
    std::copy_n(content.data() + at, piece.size(), piece.data());
    at += piece.size();
  };
  return PutDataset(sha256, name, content.size(), read, std::max<std::size_t>(1, content.size()),
                    owner, now_unix_s);
}

bool JobStore::PutDataset(const std::string& sha256, const std::string& name, std::uint64_t size,
                          const ReadBytes& read, std::size_t piece_bytes, const std::string& owner,
                          double now_unix_s) {
  if (piece_bytes == 0) throw Error("database: a dataset stored in pieces of 0 bytes");
  const auto own = [&] {
    db_.Prepare(
           "INSERT INTO dataset_owners (sha256, owner, size, uploaded) VALUES (?1, ?2, ?3, ?4)"
           " ON CONFLICT (sha256, owner) DO UPDATE SET uploaded = excluded.uploaded")
        .Bind(1, sha256)
        .Bind(2, owner)
        .Bind(3, static_cast<std::int64_t>(size))
        .Bind(4, now_unix_s)
        .Run();
  };
  std::int64_t row = -1;
  {
    // The pieces' commits need not reach the disk one by one: the owner's commit below, fully
    // synchronised, carries them all there, for the WAL is one file written in order.
    const Synchronous relaxed(db_, "NORMAL");
    bool present = false;
    db_.Transaction([&] {
      // Stored already: held at once, in the transaction that found the bytes, so that no
      // collection can drop them in between.
      present = HasDataset(sha256);
      if (present) {
        own();
        return;
      }
      db_.Prepare("INSERT INTO datasets (sha256, name, content) VALUES (?1, ?2, zeroblob(?3))")
          .Bind(1, sha256)
          .Bind(2, name)
          .Bind(3, static_cast<std::int64_t>(size))
          .Run();
      row = db_.LastInsertId();
    });
    if (present) return false;
    try {
      std::string piece;
      for (std::uint64_t offset = 0; offset < size;) {
        db_.Transaction([&] {
          Blob blob = db_.OpenBlob("datasets", "content", row);
          const std::uint64_t end = std::min(size, offset + kBytesPerTransaction);
          while (offset < end) {
            piece.resize(
                static_cast<std::size_t>(std::min<std::uint64_t>(piece_bytes, end - offset)));
            read(piece);
            blob.Write(offset, piece);
            offset += piece.size();
          }
        });
      }
    } catch (...) {
      DropRow(row);
      throw;
    }
  }
  try {
    db_.Transaction(own);
  } catch (...) {
    DropRow(row);
    throw;
  }
  return true;
}

void JobStore::DropRow(std::int64_t row) noexcept {
  if (row < 0) return;
  try {
    db_.Prepare("DELETE FROM datasets WHERE rowid = ?1").Bind(1, row).Run();
  } catch (const std::exception&) {
    // The database refuses even that (its disk is full): the row, held by nobody, is dropped
    // by DropUnheldDatasets at the next start.
  }
}

std::size_t JobStore::DropUnheldDatasets() {
  std::size_t dropped = 0;
  db_.Transaction([&] {
    std::vector<std::string> unowned;
    Statement q = db_.Prepare(
        "SELECT sha256 FROM datasets WHERE sha256 NOT IN (SELECT sha256 FROM dataset_owners)");
    while (q.Step()) unowned.push_back(q.Text(0));
    dropped = DropIfUnheld(unowned, DatasetsReadByJobs());
  });
  return dropped;
}

std::set<std::pair<std::string, std::string>> JobStore::DatasetsReadByJobs() {
  std::set<std::pair<std::string, std::string>> read_by;
  Statement jobs = db_.Prepare("SELECT owner, spec FROM jobs");
  while (jobs.Step()) {
    proto::JobSpec spec;
    if (!spec.ParseFromString(jobs.Text(1))) throw Error("database: a job's spec is corrupt");
    for (std::string& sha : SpecDatasets(spec)) read_by.emplace(jobs.Text(0), std::move(sha));
  }
  return read_by;
}

std::size_t JobStore::DropIfUnheld(const std::vector<std::string>& hashes,
                                   const std::set<std::pair<std::string, std::string>>& read_by) {
  std::set<std::string> read;
  for (const auto& [owner, sha] : read_by) read.insert(sha);
  Statement held = db_.Prepare("SELECT 1 FROM dataset_owners WHERE sha256 = ?1");
  Statement remove = db_.Prepare("DELETE FROM datasets WHERE sha256 = ?1");
  std::size_t dropped = 0;
  for (const std::string& sha : hashes) {
    const bool owned = held.Bind(1, sha).Step();
    held.Reset();
    if (owned || read.contains(sha)) continue;
    remove.Bind(1, sha).Run();
    dropped += static_cast<std::size_t>(db_.Changes());
  }
  return dropped;
}

bool JobStore::OwnsDataset(const std::string& sha256, const std::string& owner) {
  Statement q = db_.Prepare("SELECT 1 FROM dataset_owners WHERE sha256 = ?1 AND owner = ?2");
  q.Bind(1, sha256).Bind(2, owner);
  return q.Step();
}

bool JobStore::ClaimDataset(const std::string& sha256, const std::string& owner,
                            double now_unix_s) {
  Statement update =
      db_.Prepare("UPDATE dataset_owners SET uploaded = ?3 WHERE sha256 = ?1 AND owner = ?2");
  update.Bind(1, sha256).Bind(2, owner).Bind(3, now_unix_s).Run();
  return db_.Changes() > 0;
}

std::uint64_t JobStore::StoredBytes(const std::string& owner) {
  Statement datasets =
      db_.Prepare("SELECT COALESCE(SUM(size), 0) FROM dataset_owners WHERE owner = ?1");
  datasets.Bind(1, owner).Step();
  Statement results = db_.Prepare(
      "SELECT COALESCE(SUM(length(r.content)), 0) FROM results r JOIN jobs j ON r.job = j.id"
      " WHERE j.owner = ?1");
  results.Bind(1, owner).Step();
  return static_cast<std::uint64_t>(datasets.Int(0) + results.Int(0));
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

std::string JobStore::AddJob(const proto::JobSpec& spec, const std::string& owner,
                             double now_unix_s, const Submit& submit) {
  const std::string id = NewJobId();
  Statement insert = db_.Prepare(
      "INSERT INTO jobs (kind, spec, state, submitted, public_id, owner, submit_id, submit_sha256)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
  insert.Bind(1, static_cast<std::int64_t>(spec.kind()))
      .BindBlob(2, spec.SerializeAsString())
      .Bind(3, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .Bind(4, now_unix_s)
      .Bind(5, id)
      .Bind(6, owner)
      .Bind(7, submit.id)
      .Bind(8, submit.spec_sha256)
      .Run();
  return id;
}

std::optional<JobStore::Submitted> JobStore::FindSubmit(const std::string& owner,
                                                        const std::string& submit_id) {
  if (submit_id.empty()) return std::nullopt;
  Statement q =
      db_.Prepare("SELECT public_id, submit_sha256 FROM jobs WHERE owner = ?1 AND submit_id = ?2");
  q.Bind(1, owner).Bind(2, submit_id);
  if (!q.Step()) return std::nullopt;
  return Submitted{q.Text(0), q.Text(1)};
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

std::optional<std::string> JobStore::Owner(const std::string& job_id) {
  Statement q = db_.Prepare("SELECT owner FROM jobs WHERE id = ?1");
  q.Bind(1, JobNumber(job_id));
  if (!q.Step()) return std::nullopt;
  return q.Text(0);
}

std::vector<proto::JobStatus> JobStore::Jobs(const std::optional<std::string>& owner) {
  Statement q = db_.Prepare(std::string("SELECT ") + kStatusColumns +
                            " FROM jobs WHERE ?1 IS NULL OR owner = ?1 ORDER BY id");
  if (owner) q.Bind(1, *owner);
  std::vector<proto::JobStatus> jobs;
  while (q.Step()) jobs.push_back(StatusFrom(q));
  return jobs;
}

std::vector<std::string> JobStore::Unfinished() {
  Statement q = db_.Prepare("SELECT public_id FROM jobs WHERE state IN (?1, ?2) ORDER BY id");
  q.Bind(1, static_cast<std::int64_t>(proto::JOB_STATE_QUEUED))
      .Bind(2, static_cast<std::int64_t>(proto::JOB_STATE_RUNNING));
  std::vector<std::string> ids;
  while (q.Step()) ids.push_back(q.Text(0));
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

JobStore::Totals JobStore::CountTotals() {
  // One statement is one snapshot of the database: the jobs and the bytes agree, whatever
  // another connection commits meanwhile. length() of a blob reads its size from the row's
  // header, not its pages. The bytes come as the row of state -1.
  Statement q = db_.Prepare(
      "SELECT state, COUNT(*) FROM jobs GROUP BY state"
      " UNION ALL SELECT -1, (SELECT COALESCE(SUM(length(content)), 0) FROM datasets)"
      " + (SELECT COALESCE(SUM(length(content)), 0) FROM results)");
  Totals totals;
  while (q.Step()) {
    const auto count = static_cast<std::uint64_t>(q.Int(1));
    if (q.Int(0) < 0) {
      totals.stored_bytes = count;
    } else {
      totals.jobs[static_cast<proto::JobState>(q.Int(0))] = count;
    }
  }
  return totals;
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

JobStore::Collected JobStore::Collect(double now_unix_s, double retention_s) {
  const double before = now_unix_s - retention_s;
  Collected collected;
  db_.Transaction([&] {
    const std::string ended =
        std::string("SELECT id FROM jobs WHERE state IN ") + kFinishedStates + " AND finished < ?1";
    for (const char* table : {"results", "checkpoints"}) {
      db_.Prepare(std::string("DELETE FROM ") + table + " WHERE job IN (" + ended + ")")
          .Bind(1, before)
          .Run();
    }
    db_.Prepare(std::string("DELETE FROM jobs WHERE state IN ") + kFinishedStates +
                " AND finished < ?1")
        .Bind(1, before)
        .Run();
    collected.jobs = static_cast<std::size_t>(db_.Changes());

    const auto read_by = DatasetsReadByJobs();  // (owner, sha256) a job reads
    std::vector<std::pair<std::string, std::string>> unheld;
    Statement stale = db_.Prepare("SELECT owner, sha256 FROM dataset_owners WHERE uploaded < ?1");
    stale.Bind(1, before);
    while (stale.Step()) {
      std::pair<std::string, std::string> held{stale.Text(0), stale.Text(1)};
      if (!read_by.contains(held)) unheld.push_back(std::move(held));
    }
    Statement drop = db_.Prepare("DELETE FROM dataset_owners WHERE owner = ?1 AND sha256 = ?2");
    std::vector<std::string> released;
    for (const auto& [owner, sha] : unheld) {
      drop.Bind(1, owner).Bind(2, sha).Run();
      released.push_back(sha);
    }
    // Only bytes whose last owner went now: bytes that never had one are a store under way.
    collected.datasets = DropIfUnheld(released, read_by);
  });
  return collected;
}

}  // namespace evoslam
