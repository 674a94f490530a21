// The coordinator's Prometheus metrics, fetched over HTTP as a Prometheus server would, and the
// addresses it refuses to serve them on.

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "tests/service_fixture.h"

// Last: it includes glibc's <resolv.h>, whose `_res` macro breaks the Eigen headers after it.
#include <httplib.h>

namespace evoslam::service_test {
namespace {

// The value of `series` (a metric's name and labels) in a scrape; nullopt when it is absent.
std::optional<double> Sample(const std::string& scrape, const std::string& series) {
  std::istringstream in(scrape);
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with(series + " ")) return std::stod(line.substr(series.size() + 1));
  }
  return std::nullopt;
}

// HOST:PORT of the metrics, as the coordinator's log says it serves them.
std::pair<std::string, int> MetricsAddress(ChildProcess& coordinator) {
  static const std::regex kMetrics(R"(metrics on http://([0-9.]+):(\d+)/metrics)");
  const std::string log = coordinator.Log();
  std::smatch match;
  if (!std::regex_search(log, match, kMetrics)) {
    throw std::runtime_error("the coordinator says nothing of its metrics:\n" + log);
  }
  return {match[1], std::stoi(match[2])};
}

TEST_F(ServiceTest, TheCoordinatorServesMetricsOfItsJobsTasksAndWorkers) {
  const CoordinatorProcess c = StartCoordinator("coordinator", {"--metrics", "127.0.0.1:0"});
  const auto [host, port] = MetricsAddress(*c.process);
  httplib::Client http(host, port);
  const auto scrape = [&] {
    const httplib::Result r = http.Get("/metrics");
    if (!r || r->status != 200) throw std::runtime_error("no metrics at /metrics");
    return r->body;
  };
  const std::string before = scrape();
  EXPECT_EQ(Sample(before, "evoslam_jobs{state=\"succeeded\"}"), 0.0) << before;
  EXPECT_EQ(Sample(before, "evoslam_task_latency_seconds_count"), 0.0) << before;

  StartWorker("worker", c.workers);
  evoslam::ServiceClient client = Client(c.clients);
  WaitForWorkers(client, 1);
  const std::string id = SubmitDetached(Job{.scans = Scans(5)}, c.clients);
  ASSERT_EQ(WaitForEnd(client, id).state(), proto::JOB_STATE_SUCCEEDED);
  // The figures from the database are brought up to date twice a second.
  std::string after;
  EXPECT_TRUE(WaitUntil(
      [&] {
        after = scrape();
        return Sample(after, "evoslam_jobs{state=\"succeeded\"}") == 1.0;
      },
      5s))
      << after;
  EXPECT_EQ(Sample(after, "evoslam_jobs{state=\"queued\"}"), 0.0) << after;
  EXPECT_EQ(Sample(after, "evoslam_jobs_submitted_total"), 1.0) << after;
  EXPECT_EQ(Sample(after, "evoslam_workers{state=\"live\"}"), 1.0) << after;
  EXPECT_EQ(Sample(after, "evoslam_workers{state=\"quarantined\"}"), 0.0) << after;
  EXPECT_GT(Sample(after, "evoslam_task_latency_seconds_count").value_or(0), 0.0) << after;
  EXPECT_EQ(Sample(after, "evoslam_task_latency_seconds_count"),
            Sample(after, "evoslam_task_latency_seconds_bucket{le=\"+Inf\"}"));
  EXPECT_EQ(Sample(after, "evoslam_tasks_in_flight"), 0.0) << after;
  EXPECT_EQ(Sample(after, "evoslam_uploads_in_progress"), 0.0) << after;
  // The log and map uploaded, and the job's result files.
  EXPECT_GT(Sample(after, "evoslam_stored_bytes").value_or(0),
            static_cast<double>(fs::file_size(Log()) + fs::file_size(Map())))
      << after;
  EXPECT_NE(after.find("# TYPE evoslam_task_latency_seconds histogram\n"), std::string::npos);

  const httplib::Result other = http.Get("/");
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 404);
}

// The exit status, and what it said, of a process expected to end at once.
CommandResult Ended(ChildProcess& process) {
  const auto status = process.Wait(20s);
  CommandResult r;
  r.output = process.Log();
  if (!status) throw std::runtime_error("still running:\n" + r.output);
  r.exit_code = WIFEXITED(*status) ? WEXITSTATUS(*status) : -1;
  return r;
}

TEST_F(ServiceTest, TheCoordinatorRefusesAMetricsAddressItCannotOrShouldNotServe) {
  int runs = 0;
  const auto run = [&](const std::vector<std::string>& extra) {
    const std::string name = "refused-" + std::to_string(++runs);
    std::vector<std::string> argv = {
        EVOSLAM_COORDINATOR, "--db",      Path(name + ".db"), "--clients",
        "tcp://127.0.0.1:*", "--workers", "tcp://127.0.0.1:*"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return Ended(Start(argv, name + ".log"));
  };
  for (const char* bad : {"9464", "localhost", ":9464", "127.0.0.1:65536", "http://h:1"}) {
    const CommandResult r = run({"--metrics", bad});
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("is not HOST:PORT"), std::string::npos) << bad << ": " << r.output;
  }
  // An address other hosts reach: only with --insecure.
  const CommandResult open = run({"--metrics", "0.0.0.0:0"});
  EXPECT_EQ(open.exit_code, 2) << open.output;
  EXPECT_NE(open.output.find("refusing to serve metrics on 0.0.0.0:0"), std::string::npos)
      << open.output;
  const CoordinatorProcess insecure =
      StartCoordinator("insecure", {"--metrics", "0.0.0.0:0", "--insecure"});
  EXPECT_NE(insecure.process->Log().find("serving metrics on 0.0.0.0:0 to anyone"),
            std::string::npos);
  // A port another process holds: a clear error, not a second listener on it.
  const std::string taken = "0.0.0.0:" + std::to_string(MetricsAddress(*insecure.process).second);
  const CommandResult busy = run({"--metrics", taken, "--insecure"});
  EXPECT_EQ(busy.exit_code, 1) << busy.output;
  EXPECT_NE(busy.output.find("cannot serve metrics on " + taken + ": Address already in use"),
            std::string::npos)
      << busy.output;
}

}  // namespace
}  // namespace evoslam::service_test
