#ifndef EVOSLAM_COORDINATOR_JOB_STORE_H_
#define EVOSLAM_COORDINATOR_JOB_STORE_H_

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "coordinator/sqlite.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// The coordinator's durable state in one SQLite file: uploaded datasets, jobs with their specs,
// states and results, and each island's latest checkpoint. Every change is one committed
// transaction, so after kill -9 and a restart on the same file nothing submitted is lost and
// every unfinished job can resume from its last checkpoint. One coordinator owns a file.
class JobStore {
 public:
  explicit JobStore(const std::filesystem::path& path);

  // Datasets, by the SHA-256 of their bytes (the caller has checked it), each held by the owners
  // that uploaded it (an owner is a client's CURVE public key; "" with CURVE off). PutDataset
  // records `owner` as holding it since `now_unix_s` and returns false when the bytes were
  // already stored.
  bool PutDataset(const std::string& sha256, const std::string& name, const std::string& content,
                  const std::string& owner, double now_unix_s);
  // Hands over a dataset's next bytes, in order: fills the whole span it is given.
  using ReadBytes = std::function<void(std::span<char>)>;
  // PutDataset of `size` bytes read through `read` in pieces of at most `piece_bytes`, so a large
  // dataset is never in memory whole: the row is made at its full size (zeroblob), then filled
  // in transactions of at most 32 MiB, so that other writers get the database in between. The
  // owner is recorded last, in a transaction synchronised to disk: until
  // then nobody holds the bytes, so nobody can use them half-written. A store cut short removes
  // its row; a crash part-way leaves one that DropUnheldDatasets removes.
  bool PutDataset(const std::string& sha256, const std::string& name, std::uint64_t size,
                  const ReadBytes& read, std::size_t piece_bytes, const std::string& owner,
                  double now_unix_s);
  // Drops the bytes of datasets that no owner holds and no job reads: what a store cut short by
  // a crash left behind. Returns how many.
  std::size_t DropUnheldDatasets();
  bool HasDataset(const std::string& sha256);  // held by anyone
  bool OwnsDataset(const std::string& sha256, const std::string& owner);
  // Whether `owner` holds the dataset; if so it counts as uploaded again at `now_unix_s`, so that
  // the job it is about to be submitted with finds it.
  bool ClaimDataset(const std::string& sha256, const std::string& owner, double now_unix_s);
  std::optional<std::string> Dataset(const std::string& sha256);
  // The bytes `owner` keeps here: the datasets it holds and its jobs' results.
  std::uint64_t StoredBytes(const std::string& owner);

  // What a client's submit is known by: the id the client chose for it, the same in every retry
  // of the one submit (empty: none, every such submit is a new job), and the SHA-256 of the spec
  // it sent, which tells a retry from another job reusing the id.
  struct Submit {
    std::string id;
    std::string spec_sha256;
  };
  // A new job of `owner` in state QUEUED; returns its id, "job-" and 32 random hex digits, which
  // nobody can guess. A non-empty submit id names at most one job of an owner: a second throws.
  std::string AddJob(const proto::JobSpec& spec, const std::string& owner, double now_unix_s,
                     const Submit& submit = {});
  // The job `owner` submitted under `submit_id`, while it is kept (Collect drops it, and its
  // submit id with it); nullopt when there is none or the id is empty.
  struct Submitted {
    std::string job_id;
    std::string spec_sha256;
  };
  std::optional<Submitted> FindSubmit(const std::string& owner, const std::string& submit_id);
  std::optional<proto::JobSpec> Spec(const std::string& job_id);
  std::optional<proto::JobStatus> Status(const std::string& job_id);
  std::optional<std::string> Owner(const std::string& job_id);
  // Every job, or `owner`'s alone, in the order they were submitted.
  std::vector<proto::JobStatus> Jobs(const std::optional<std::string>& owner = std::nullopt);
  // Jobs that were queued or running when the coordinator last stopped, oldest first.
  std::vector<std::string> Unfinished();

  // Marks a queued or running job running, where `progress` says it stands: its phase, done,
  // total, evaluations and step (none when `progress` has none).
  void SetRunning(const std::string& job_id, const proto::JobStatus& progress);
  // Ends a job still queued or running, dropping its checkpoints; `error` is empty unless it
  // failed. False when the job had already ended (it was cancelled meanwhile, say): a job ends
  // once.
  bool Finish(const std::string& job_id, proto::JobState state, const std::string& error,
              double now_unix_s);
  // Ends a job as succeeded with its result files, in one transaction; false as Finish.
  bool Succeed(const std::string& job_id, const std::vector<proto::ResultFile>& files,
               double now_unix_s);
  std::size_t CountUnfinished();
  // What the store keeps, read at one moment.
  struct Totals {
    std::map<proto::JobState, std::uint64_t> jobs;  // by state; a state no job is in is absent
    std::uint64_t stored_bytes = 0;  // every dataset and every job's result, each stored once
    bool operator==(const Totals&) const = default;
  };
  Totals CountTotals();

  // A job's latest checkpoints, one per slot (a localization keeps one, its whole state; an
  // island job may keep one per island), replaced as the job advances.
  void SaveCheckpoint(const std::string& job_id, std::uint32_t island, std::uint64_t epoch,
                      const std::string& bytes);
  struct Checkpoint {
    std::uint32_t island = 0;
    std::uint64_t epoch = 0;
    std::string bytes;
  };
  std::vector<Checkpoint> Checkpoints(const std::string& job_id);

  std::vector<proto::ResultFile> Result(const std::string& job_id);

  // Drops what has been kept past `retention_s`: jobs that ended before `now_unix_s -
  // retention_s`, with their results, then each owner's datasets that none of its jobs reads and
  // that it last uploaded before then, and the bytes nobody holds any more. Bytes that had no
  // owner before (a store under way) are left alone.
  struct Collected {
    std::size_t jobs = 0;
    std::size_t datasets = 0;  // whose bytes were dropped (no owner holds them any more)
  };
  Collected Collect(double now_unix_s, double retention_s);

 private:
  void SaveResult(const std::string& job_id, const std::vector<proto::ResultFile>& files);
  // The row of a job id; -1 when there is none.
  std::int64_t JobNumber(const std::string& job_id);
  // (owner, sha256) of every dataset a job reads.
  std::set<std::pair<std::string, std::string>> DatasetsReadByJobs();
  // Drops the bytes of those of `hashes` that no owner holds and no job reads; returns how many.
  std::size_t DropIfUnheld(const std::vector<std::string>& hashes,
                           const std::set<std::pair<std::string, std::string>>& read_by);
  void DropRow(std::int64_t row) noexcept;  // a datasets row a store left half-written

  Database db_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_JOB_STORE_H_
