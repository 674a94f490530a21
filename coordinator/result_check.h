#ifndef EVOSLAM_COORDINATOR_RESULT_CHECK_H_
#define EVOSLAM_COORDINATOR_RESULT_CHECK_H_

#include <optional>
#include <string>

#include "evoslam/service.pb.h"

namespace evoslam {

// What is wrong with a worker's answer to `task`, or nullopt when it may be taken: an answer of
// the kind asked for, for this task, whose numbers are all finite and fit the task's dimensions,
// and, for an island, one that advanced as asked (its generations and evaluations counted on
// from the task's, the first population drawn when asked to start). A worker's error is an answer
// too. The coordinator cannot redo the work; this refuses what a buggy or hostile worker sends
// that could only stall or corrupt the job.
std::optional<std::string> CheckResult(const proto::Task& task, const proto::TaskResult& result);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_RESULT_CHECK_H_
