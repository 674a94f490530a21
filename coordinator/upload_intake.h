#ifndef EVOSLAM_COORDINATOR_UPLOAD_INTAKE_H_
#define EVOSLAM_COORDINATOR_UPLOAD_INTAKE_H_

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stop_token>
#include <string>
#include <variant>

#include "coordinator/job_store.h"
#include "coordinator/upload_assembler.h"
#include "coordinator/upload_table.h"
#include "coordinator/work_thread.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Uploads, off the broker thread, so that the broker never waits for the database, a disk or a
// hash. The store thread, through a database connection of its own, answers each upload's start
// (the client holds the bytes already, or its quota has no room) and stores each finished
// dataset piece by piece (JobStore::PutDataset), one at a time; the spool thread writes each
// chunk to its upload's spool file, hashing it as it comes, and goes on with other uploads'
// chunks while a dataset is stored. No more of an upload than its chunks on their way is ever
// in memory. Every request handed over is answered through `deliver`; an upload's answers come
// in the order of its requests. Uploads not finished, and their spool files, go with the
// object.
class UploadIntake {
 public:
  struct Options {
    std::size_t chunk_bytes = kUploadChunkBytes;
    std::uint32_t window = kUploadWindow;
    std::uint64_t quota_bytes = 0;  // a client's stored bytes at most; 0: no limit
    bool quiet = false;             // stored datasets logged at debug level instead of info
  };
  // An answer for the broker to send to the client `identity`, about upload `upload_id`, which is
  // over (stored, or dropped after a refusal) when `ended`.
  struct Answer {
    std::string identity;
    proto::ClientReply reply;  // carries the request's id
    std::string upload_id;
    bool ended = false;
  };
  // Called on the intake's threads with every answer: it must only hand the answer over (queue
  // it and wake the broker).
  using Deliver = std::function<void(Answer)>;

  // Opens its own connection to the database at `db`. Spools into `spool_dir`, which it empties
  // first (what a coordinator killed in the middle of an upload left there) and removes when it
  // goes; throws Error when it cannot.
  UploadIntake(const std::filesystem::path& db, std::filesystem::path spool_dir, Options options,
               Deliver deliver);
  ~UploadIntake();
  UploadIntake(const UploadIntake&) = delete;
  UploadIntake& operator=(const UploadIntake&) = delete;

  // The start of upload `upload_id` of `owner`'s, at `now_unix_s`: a dataset of `size` bytes
  // (checked against the size limit already), or a question when `size` is none. Answered
  // `stored` when `owner` holds the bytes already, UNKNOWN_DATASET for a question otherwise,
  // QUOTA_EXCEEDED when the owner's stored bytes and `reserved` (those of its other uploads
  // under way) leave no room, and `upload_started` otherwise.
  void Start(std::string identity, std::uint64_t request_id, std::string upload_id,
             std::string name, std::string sha256, std::optional<std::uint64_t> size,
             std::string owner, std::uint64_t reserved, double now_unix_s);
  // A chunk; answered `chunk_stored`, or `stored` once the last is in the database.
  void Append(std::string identity, std::uint64_t request_id, proto::UploadChunk chunk);
  // Drops an upload the broker gave up on, with its spool file; not answered.
  void Drop(std::string upload_id);

 private:
  struct StartWork {
    std::string identity;
    std::uint64_t request_id = 0;
    std::string upload_id, name, sha256;
    std::optional<std::uint64_t> size;
    std::string owner;
    std::uint64_t reserved = 0;
    double started = 0;
  };
  struct ChunkWork {
    std::string identity;
    std::uint64_t request_id = 0;
    proto::UploadChunk chunk;
  };
  struct DropWork {
    std::string upload_id;
  };
  using Work = std::variant<StartWork, ChunkWork, DropWork>;

  struct Upload {
    Upload(const std::filesystem::path& spool, const StartWork& start, std::size_t chunk_bytes)
        : assembler(spool, start.upload_id, start.name, start.sha256, start.size.value_or(0),
                    chunk_bytes),
          owner(start.owner),
          started(start.started) {}
    UploadAssembler assembler;
    std::string owner;
    double started;
  };
  using Uploads = std::map<std::string, Upload>;
  // A complete upload on its way to the database, and whom to tell when it is there.
  struct StoreWork {
    std::string identity;
    std::uint64_t request_id = 0;
    Uploads::node_type upload;
  };
  using DatabaseWork = std::variant<StartWork, StoreWork>;

  // The spool folder, emptied when made and removed when it goes.
  class SpoolDir {
   public:
    explicit SpoolDir(std::filesystem::path path);
    ~SpoolDir();
    SpoolDir(const SpoolDir&) = delete;
    SpoolDir& operator=(const SpoolDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

   private:
    std::filesystem::path path_;
  };

  // The spool thread.
  void Spool(Work& work);
  void Do(StartWork& work);
  void Do(ChunkWork& work);
  void Do(DropWork& work);
  // The store thread.
  void Begin(StartWork& work);
  void Store(StoreWork& work, const std::stop_token& stop);

  JobStore store_;  // the store thread's own connection
  SpoolDir spool_dir_;
  Options options_;
  Deliver deliver_;
  Uploads uploads_;  // the spool thread's
  // Last: they stop, both, before what they use goes, for each posts to the other.
  WorkThread<DatabaseWork> storer_;
  WorkThread<Work> spooler_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_UPLOAD_INTAKE_H_
