#include "coordinator/metrics.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

namespace evoslam {
namespace {

TEST(MetricsTest, RendersThePrometheusTextFormat) {
  Metrics metrics;
  metrics.SetStored({{proto::JOB_STATE_QUEUED, 2}, {proto::JOB_STATE_SUCCEEDED, 5}}, 123456789012);
  metrics.CountSubmit();
  metrics.CountSubmit();
  metrics.CountRepeatedSubmit();
  metrics.SetTasks(3, 7);
  metrics.ObserveTaskLatency(0.00390625);  // 2^-8: the sum is exact
  metrics.ObserveTaskLatency(0.75);
  metrics.ObserveTaskLatency(1000);
  metrics.SetWorkers(4, 1);
  metrics.SetUploadsInProgress(1);
  EXPECT_EQ(metrics.Render(),
            "# HELP evoslam_jobs Jobs the coordinator keeps (ended ones until the retention drops "
            "them), by state.\n"
            "# TYPE evoslam_jobs gauge\n"
            "evoslam_jobs{state=\"queued\"} 2\n"
            "evoslam_jobs{state=\"running\"} 0\n"
            "evoslam_jobs{state=\"succeeded\"} 5\n"
            "evoslam_jobs{state=\"failed\"} 0\n"
            "evoslam_jobs{state=\"cancelled\"} 0\n"
            "# HELP evoslam_jobs_submitted_total Jobs submitted since the coordinator started.\n"
            "# TYPE evoslam_jobs_submitted_total counter\n"
            "evoslam_jobs_submitted_total 2\n"
            "# HELP evoslam_submits_repeated_total Submits answered with the job an earlier send "
            "of the same submit id made.\n"
            "# TYPE evoslam_submits_repeated_total counter\n"
            "evoslam_submits_repeated_total 1\n"
            "# HELP evoslam_tasks_in_flight Tasks sent to workers and not answered yet.\n"
            "# TYPE evoslam_tasks_in_flight gauge\n"
            "evoslam_tasks_in_flight 3\n"
            "# HELP evoslam_tasks_waiting Tasks waiting for an idle worker.\n"
            "# TYPE evoslam_tasks_waiting gauge\n"
            "evoslam_tasks_waiting 7\n"
            "# HELP evoslam_task_latency_seconds Time from a task's dispatch to a worker to its "
            "accepted result.\n"
            "# TYPE evoslam_task_latency_seconds histogram\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.005\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.01\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.025\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.05\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.1\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.25\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"0.5\"} 1\n"
            "evoslam_task_latency_seconds_bucket{le=\"1\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"2.5\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"5\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"10\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"30\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"60\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"120\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"300\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"600\"} 2\n"
            "evoslam_task_latency_seconds_bucket{le=\"+Inf\"} 3\n"
            "evoslam_task_latency_seconds_sum 1000.75390625\n"
            "evoslam_task_latency_seconds_count 3\n"
            "# HELP evoslam_workers Workers connected, by state: live (in the pool) or quarantined "
            "(out of it for failing).\n"
            "# TYPE evoslam_workers gauge\n"
            "evoslam_workers{state=\"live\"} 4\n"
            "evoslam_workers{state=\"quarantined\"} 1\n"
            "# HELP evoslam_stored_bytes Bytes of datasets and job results in the coordinator's "
            "database.\n"
            "# TYPE evoslam_stored_bytes gauge\n"
            "evoslam_stored_bytes 123456789012\n"
            "# HELP evoslam_uploads_in_progress Dataset uploads under way.\n"
            "# TYPE evoslam_uploads_in_progress gauge\n"
            "evoslam_uploads_in_progress 1\n");
}

// A bucket counts every observation at or under its bound.
TEST(MetricsTest, ALatencyOnABucketsBoundCountsInIt) {
  Metrics metrics;
  metrics.ObserveTaskLatency(0.1);
  const MetricsSnapshot s = metrics.Snapshot();
  EXPECT_EQ(s.task_latency_buckets[3], 0u);  // 0.05
  EXPECT_EQ(s.task_latency_buckets[4], 1u);  // 0.1
  EXPECT_EQ(s.task_latency_count, 1u);
  EXPECT_EQ(s.task_latency_sum_seconds, 0.1);
}

// Figures change on one thread while another renders them (run under ThreadSanitizer or
// AddressSanitizer, a race would show).
TEST(MetricsTest, RenderingWhileFiguresChangeIsSafe) {
  Metrics metrics;
  std::jthread changer([&] {
    for (int i = 0; i < 2000; ++i) {
      metrics.ObserveTaskLatency(0.01 * i);
      metrics.SetWorkers(static_cast<std::uint64_t>(i), 0);
    }
  });
  for (int i = 0; i < 200; ++i) EXPECT_FALSE(metrics.Render().empty());
  changer.join();
  EXPECT_EQ(metrics.Snapshot().task_latency_count, 2000u);
}

}  // namespace
}  // namespace evoslam
