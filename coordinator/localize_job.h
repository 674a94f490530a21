#ifndef EVOSLAM_COORDINATOR_LOCALIZE_JOB_H_
#define EVOSLAM_COORDINATOR_LOCALIZE_JOB_H_

#include <vector>

#include "coordinator/job_context.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Runs a localization job: the coordinator holds the map and the trajectory and sends each
// scan's search to the workers (one task per island and epoch, or per batch of an exhaustive
// search). Returns the job's output files. Throws JobInterrupted when cancelled or shut down,
// Error when the job cannot run.
std::vector<proto::ResultFile> RunLocalizeJob(const JobContext& context);

// The problem a task of this job refers to: the job's datasets and parameters.
proto::ProblemSpec LocalizeProblemOf(const proto::JobSpec& spec);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_LOCALIZE_JOB_H_
