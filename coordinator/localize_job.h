#ifndef EVOSLAM_COORDINATOR_LOCALIZE_JOB_H_
#define EVOSLAM_COORDINATOR_LOCALIZE_JOB_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/service/dataset_files.h"
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

// Runs a localization job: the coordinator holds the map and the trajectory and sends each
// scan's search to the workers (one task per island and epoch, or per batch of an exhaustive
// search). Returns the job's output files. Throws JobInterrupted when cancelled or shut down,
// Error when the job cannot run.
std::vector<proto::ResultFile> RunLocalizeJob(const JobContext& context);

// The problem a task of this job refers to: the job's datasets and parameters.
proto::ProblemSpec LocalizeProblemOf(const proto::JobSpec& spec);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_LOCALIZE_JOB_H_
