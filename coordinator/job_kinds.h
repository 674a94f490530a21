#ifndef EVOSLAM_COORDINATOR_JOB_KINDS_H_
#define EVOSLAM_COORDINATOR_JOB_KINDS_H_

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "coordinator/job_context.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// What differs between the kinds of job the coordinator runs (localize, SLAM): what a submitted
// spec must hold, which datasets it reads, and which job thread runs it.

// Checks a submitted spec, refusing a kind this coordinator does not run, parameters missing or
// of another kind, datasets the kind does not read, and bad parameters (Error naming the field).
// The spec's seed and island count, when given, become its parameters'.
void PrepareJobSpec(proto::JobSpec& spec);

// The datasets a job reads, each with what it is ("log", "map", ...) for messages: the log, the
// map for a localization, and the map image and relations when the spec names them.
std::vector<std::pair<const char*, proto::DatasetRef>> JobDatasets(const proto::JobSpec& spec);

// Refuses (Error) a spec whose files refer to any file but one another: a map_server map must
// name the image uploaded with it. `content` returns a dataset's stored bytes.
void CheckJobFileReferences(const proto::JobSpec& spec,
                            const std::function<std::string(const proto::DatasetRef&)>& content);

// Runs the job of the context's spec with the runner of its kind.
std::vector<proto::ResultFile> RunJobOfKind(const JobContext& context);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_JOB_KINDS_H_
