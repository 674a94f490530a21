#include "coordinator/metrics.h"

#include <fmt/format.h>

#include <iterator>
#include <string_view>

#include "common/service/job_state.h"

namespace evoslam {
namespace {

// Appends the HELP and TYPE lines of metric `name`.
void Describe(std::string& out, std::string_view name, std::string_view type,
              std::string_view help) {
  fmt::format_to(std::back_inserter(out), "# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
}

// Appends a metric of one sample.
template <typename Value>
void Single(std::string& out, std::string_view name, std::string_view type, std::string_view help,
            Value value) {
  Describe(out, name, type, help);
  fmt::format_to(std::back_inserter(out), "{} {}\n", name, value);
}

}  // namespace

std::string RenderPrometheus(const MetricsSnapshot& s) {
  std::string out;
  const auto sample = [&](std::string_view name, std::string_view labels, auto value) {
    fmt::format_to(std::back_inserter(out), "{}{{{}}} {}\n", name, labels, value);
  };
  Describe(out, "evoslam_jobs", "gauge",
           "Jobs the coordinator keeps (ended ones until the retention drops them), by state.");
  for (std::size_t i = 0; i < kJobStates.size(); ++i) {
    sample("evoslam_jobs", fmt::format("state=\"{}\"", JobStateName(kJobStates[i])), s.jobs[i]);
  }
  Single(out, "evoslam_jobs_submitted_total", "counter",
         "Jobs submitted since the coordinator started.", s.jobs_submitted);
  Single(out, "evoslam_submits_repeated_total", "counter",
         "Submits answered with the job an earlier send of the same submit id made.",
         s.submits_repeated);
  Single(out, "evoslam_tasks_in_flight", "gauge", "Tasks sent to workers and not answered yet.",
         s.tasks_in_flight);
  Single(out, "evoslam_tasks_waiting", "gauge", "Tasks waiting for an idle worker.",
         s.tasks_waiting);
  Describe(out, "evoslam_task_latency_seconds", "histogram",
           "Time from a task's dispatch to a worker to its accepted result.");
  for (std::size_t i = 0; i < kTaskLatencyBuckets.size(); ++i) {
    sample("evoslam_task_latency_seconds_bucket", fmt::format("le=\"{}\"", kTaskLatencyBuckets[i]),
           s.task_latency_buckets[i]);
  }
  sample("evoslam_task_latency_seconds_bucket", "le=\"+Inf\"", s.task_latency_count);
  fmt::format_to(std::back_inserter(out),
                 "evoslam_task_latency_seconds_sum {}\nevoslam_task_latency_seconds_count {}\n",
                 s.task_latency_sum_seconds, s.task_latency_count);
  Describe(out, "evoslam_workers", "gauge",
           "Workers connected, by state: live (in the pool) or quarantined (out of it for "
           "failing).");
  sample("evoslam_workers", "state=\"live\"", s.workers_live);
  sample("evoslam_workers", "state=\"quarantined\"", s.workers_quarantined);
  Single(out, "evoslam_stored_bytes", "gauge",
         "Bytes of datasets and job results in the coordinator's database.", s.stored_bytes);
  Single(out, "evoslam_uploads_in_progress", "gauge", "Dataset uploads under way.",
         s.uploads_in_progress);
  return out;
}

void Metrics::SetStored(const std::map<proto::JobState, std::uint64_t>& jobs_by_state,
                        std::uint64_t bytes) {
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < kJobStates.size(); ++i) {
    const auto it = jobs_by_state.find(kJobStates[i]);
    figures_.jobs[i] = it == jobs_by_state.end() ? 0 : it->second;
  }
  figures_.stored_bytes = bytes;
}

void Metrics::SetTasks(std::uint64_t in_flight, std::uint64_t waiting) {
  std::lock_guard lock(mutex_);
  figures_.tasks_in_flight = in_flight;
  figures_.tasks_waiting = waiting;
}

void Metrics::SetWorkers(std::uint64_t live, std::uint64_t quarantined) {
  std::lock_guard lock(mutex_);
  figures_.workers_live = live;
  figures_.workers_quarantined = quarantined;
}

void Metrics::SetUploadsInProgress(std::uint64_t uploads) {
  std::lock_guard lock(mutex_);
  figures_.uploads_in_progress = uploads;
}

void Metrics::CountSubmit() {
  std::lock_guard lock(mutex_);
  ++figures_.jobs_submitted;
}

void Metrics::CountRepeatedSubmit() {
  std::lock_guard lock(mutex_);
  ++figures_.submits_repeated;
}

void Metrics::ObserveTaskLatency(double seconds) {
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < kTaskLatencyBuckets.size(); ++i) {
    if (seconds <= kTaskLatencyBuckets[i]) ++figures_.task_latency_buckets[i];
  }
  ++figures_.task_latency_count;
  figures_.task_latency_sum_seconds += seconds;
}

MetricsSnapshot Metrics::Snapshot() const {
  std::lock_guard lock(mutex_);
  return figures_;
}

}  // namespace evoslam
