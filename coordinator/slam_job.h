#ifndef EVOSLAM_COORDINATOR_SLAM_JOB_H_
#define EVOSLAM_COORDINATOR_SLAM_JOB_H_

#include <vector>

#include "coordinator/job_context.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// Runs a SLAM job with its method: the coordinator's job thread holds the map and the trajectory
// and runs the method's own steps; its island searches go to the workers, one task per island
// and epoch. Returns the job's output files. Throws JobInterrupted when cancelled or shut down,
// Error when the job cannot run.
std::vector<proto::ResultFile> RunSlamJob(const JobContext& context);

// What every task of this job refers to: its log and its parameters, every one set (so that a
// worker whose defaults differ rebuilds the same problem); each task adds its method's task.
proto::ProblemSpec SlamProblemOf(const proto::JobSpec& spec);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_SLAM_JOB_H_
