#ifndef EVOSLAM_COORDINATOR_JOB_CONTEXT_H_
#define EVOSLAM_COORDINATOR_JOB_CONTEXT_H_

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/engine/island.h"
#include "common/service/dataset_files.h"
#include "common/util/error.h"
#include "coordinator/task_board.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// What a job's thread needs from the coordinator around it.
struct JobContext {
  std::string job_id;
  proto::JobSpec spec;
  TaskBoard* board = nullptr;
  DatasetFiles* files = nullptr;  // the job's datasets are there already
  // The last checkpoint saved, to resume from (serialised).
  std::optional<std::string> resume;
  // Saves a checkpoint (serialised); called at most every `checkpoint_seconds` seconds.
  std::function<void(const std::string& bytes)> save_checkpoint;
  double checkpoint_seconds = 0.0;
  std::function<void(const proto::JobStatus& progress)> progress;
  std::uint32_t worker_threads = 0;  // for the report
};

// Saves a job's checkpoints through its context, at most one every checkpoint_seconds: a job
// offers one after every step, and only those far enough apart cost a database write.
class CheckpointThrottle {
 public:
  explicit CheckpointThrottle(const JobContext& context);
  // Saves what `serialize` returns, unless the last save was too recent.
  void Offer(const std::function<std::string()>& serialize);

 private:
  const JobContext& context_;
  std::chrono::steady_clock::time_point last_save_;
};

// The state a job resumes from: its last checkpoint, a `Checkpoint` message, as `from_proto`
// reads it; nullopt for a job starting afresh. Throws Error for a checkpoint that cannot be read.
template <typename Checkpoint, typename FromProto>
auto ResumeState(const JobContext& context, FromProto from_proto)
    -> std::optional<decltype(from_proto(Checkpoint()))> {
  if (!context.resume) return std::nullopt;
  Checkpoint checkpoint;
  if (!checkpoint.ParseFromString(*context.resume)) {
    throw Error("the job's checkpoint is unreadable");
  }
  return from_proto(checkpoint);
}

// Tells the coordinator where the job stands: `done` of its `total` scans, the fitness
// evaluations so far, and the step under way inside it (none when `step` has no name). The phase
// is the job's kind ("slam", "localize").
void ReportProgress(const JobContext& context, std::uint64_t done, std::uint64_t total,
                    std::uint64_t evaluations, const proto::JobStep& step = {});

// Starts (when `start`) and evolves each island for up to `generations` generations on the
// workers, one EvolveIsland task per island on `problem`; the islands come back in place.
// Throws JobInterrupted when the job is cancelled, Error when a worker fails a task.
void EvolveIslandsRemotely(const JobContext& context, const proto::ProblemSpec& problem,
                           std::vector<Island>& islands, bool start, std::size_t generations);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_JOB_CONTEXT_H_
