#ifndef EVOSLAM_COORDINATOR_METRICS_H_
#define EVOSLAM_COORDINATOR_METRICS_H_

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "evoslam/service.pb.h"

namespace evoslam {

// Upper bounds of the task latency histogram's buckets, in seconds: from a batch of evaluations
// (milliseconds) to an island epoch of a large SLAM job (minutes), up to the default task
// timeout of 600 s.
inline constexpr std::array<double, 16> kTaskLatencyBuckets = {
    0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30, 60, 120, 300, 600};

// The jobs of each state, in the order they are rendered.
inline constexpr std::array<proto::JobState, 5> kJobStates = {
    proto::JOB_STATE_QUEUED, proto::JOB_STATE_RUNNING, proto::JOB_STATE_SUCCEEDED,
    proto::JOB_STATE_FAILED, proto::JOB_STATE_CANCELLED};

// The coordinator's figures at one moment.
struct MetricsSnapshot {
  std::array<std::uint64_t, kJobStates.size()> jobs{};  // kept in the store, by kJobStates
  std::uint64_t jobs_submitted = 0;                     // since the coordinator started
  std::uint64_t submits_repeated = 0;  // answered with the job an earlier send made
  std::uint64_t tasks_in_flight = 0;   // held by workers, unanswered
  std::uint64_t tasks_waiting = 0;     // posted, waiting for an idle worker
  // Tasks answered within each of kTaskLatencyBuckets (cumulative, as Prometheus has them).
  std::array<std::uint64_t, kTaskLatencyBuckets.size()> task_latency_buckets{};
  std::uint64_t task_latency_count = 0;
  double task_latency_sum_seconds = 0;
  std::uint64_t workers_live = 0;         // connected and in the pool
  std::uint64_t workers_quarantined = 0;  // connected, out of the pool for failing
  std::uint64_t stored_bytes = 0;         // datasets and results in the database
  std::uint64_t uploads_in_progress = 0;
};

// The snapshot in Prometheus's text exposition format (version 0.0.4): a HELP and a TYPE line
// for each metric, names prefixed evoslam_, counters ending _total, the latency a histogram in
// seconds.
std::string RenderPrometheus(const MetricsSnapshot& snapshot);

// The figures the coordinator exposes (metrics_server.h serves them). The broker thread, the job
// threads and whoever handles uploads change them; any thread renders them. One mutex guards
// them all: every change is a few additions.
class Metrics {
 public:
  // The figures read from the database, set together so that no scrape sees a job's end
  // without its result's bytes.
  void SetStored(const std::map<proto::JobState, std::uint64_t>& jobs_by_state,
                 std::uint64_t bytes);
  void SetTasks(std::uint64_t in_flight, std::uint64_t waiting);
  void SetWorkers(std::uint64_t live, std::uint64_t quarantined);
  void SetUploadsInProgress(std::uint64_t uploads);
  void CountSubmit();          // a submit that made a job
  void CountRepeatedSubmit();  // a submit answered with the job an earlier send made
  void ObserveTaskLatency(double seconds);

  MetricsSnapshot Snapshot() const;
  std::string Render() const { return RenderPrometheus(Snapshot()); }

 private:
  mutable std::mutex mutex_;
  MetricsSnapshot figures_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_METRICS_H_
