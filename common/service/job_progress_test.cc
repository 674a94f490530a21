#include "common/service/job_progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <string>

#include "common/util/progress_bar_testing.h"

namespace evoslam {
namespace {

using std::chrono::seconds;

proto::JobStatus Status(const std::string& phase, std::uint64_t done, std::uint64_t total) {
  proto::JobStatus s;
  s.set_kind(proto::JOB_KIND_SLAM);
  s.set_state(proto::JOB_STATE_RUNNING);
  s.set_phase(phase);
  s.set_done(done);
  s.set_total(total);
  return s;
}

proto::JobStatus Searching(std::uint64_t done, std::uint64_t generations) {
  proto::JobStatus s = Status("slam", done, 300);
  s.mutable_step()->set_name("global search");
  s.mutable_step()->set_done(generations);
  s.mutable_step()->set_total(100);
  return s;
}

TEST(JobProgressTest, TheStepIsItsNameAndCounts) {
  EXPECT_EQ(StepText(Status("slam", 1, 2)), "");
  EXPECT_EQ(StepText(Searching(1, 30)), "global search 30/100");
}

// Loading, scans, a global search inside them and scans again: one bar, over the job's scans, its
// clock running from the first scan count; the search shows inside it, never as a bar of its own.
TEST(JobProgressTest, OneBarForTheWholeJobWithTheStepInside) {
  testing::CapturedFile out;
  testing::FakeClock clock;
  JobProgress progress(testing::BarTo(out, clock));
  progress.Show(Status("loading", 0, 0));
  clock.Advance(seconds(5));
  progress.Show(Status("slam", 0, 300));
  clock.Advance(seconds(2));
  progress.Show(Searching(100, 0));
  EXPECT_NE(out.line().find("100/300 scans   33%  0:02 elapsed, 0:04 left  · global search 0/100"),
            std::string::npos)
      << out.line();
  clock.Advance(seconds(2));
  progress.Show(Searching(100, 50));
  EXPECT_NE(out.line().find("100/300 scans   33%  0:04 elapsed, 0:08 left  · global search 50/100"),
            std::string::npos)
      << out.line();
  clock.Advance(seconds(1));
  progress.Show(Status("slam", 101, 300));
  EXPECT_NE(out.line().find("101/300 scans   33%  0:05 elapsed"), std::string::npos) << out.line();
  EXPECT_EQ(out.line().find("global search"), std::string::npos) << out.line();

  // Every line drawn is the job's.
  const std::string all = out.text();
  std::size_t lines = 0;
  for (std::size_t at = all.find('\r'); at != std::string::npos; at = all.find('\r', at + 1)) {
    const std::string line = all.substr(at + 1, all.find("\033[K", at) - at - 1);
    EXPECT_TRUE(line.starts_with("slam  [")) << line;
    EXPECT_NE(line.find("/300 scans"), std::string::npos) << line;
    ++lines;
  }
  EXPECT_EQ(lines, 3u);
}

}  // namespace
}  // namespace evoslam
