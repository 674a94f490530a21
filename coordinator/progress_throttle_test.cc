#include "coordinator/progress_throttle.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace evoslam {
namespace {

using Clock = ProgressThrottle::Clock;
using std::chrono::milliseconds;

proto::JobStatus Report(std::uint64_t done, std::uint64_t total) {
  proto::JobStatus s;
  s.set_phase("slam");
  s.set_done(done);
  s.set_total(total);
  return s;
}

// A report at `done` scans with a global search `search_done` generations in.
proto::JobStatus Searching(std::uint64_t done, std::uint64_t total, std::uint64_t search_done) {
  proto::JobStatus s = Report(done, total);
  s.mutable_step()->set_name("global search");
  s.mutable_step()->set_done(search_done);
  s.mutable_step()->set_total(20);
  return s;
}

TEST(ProgressThrottleTest, WithinAPhaseOneReportPerIntervalAndTheLastAreKept) {
  ProgressThrottle throttle(milliseconds(200));
  const Clock::time_point t0 = Clock::now();
  EXPECT_TRUE(throttle.Admit(Report(1, 100), t0));
  EXPECT_FALSE(throttle.Admit(Report(2, 100), t0 + milliseconds(10)));
  EXPECT_FALSE(throttle.Admit(Report(40, 100), t0 + milliseconds(199)));
  EXPECT_TRUE(throttle.Admit(Report(41, 100), t0 + milliseconds(200)));
  // The interval runs from the last report kept, not from the last one offered.
  EXPECT_FALSE(throttle.Admit(Report(42, 100), t0 + milliseconds(390)));
  EXPECT_TRUE(throttle.Admit(Report(43, 100), t0 + milliseconds(400)));
  EXPECT_TRUE(throttle.Admit(Report(100, 100), t0 + milliseconds(401)));
}

// Scans, a global search, a short stretch of scans and another global search, each far shorter
// than the interval: each shows once a tenth of the interval has passed since the last record.
TEST(ProgressThrottleTest, ANewStepShowsAfterATenthOfTheInterval) {
  ProgressThrottle throttle(milliseconds(200));
  const Clock::time_point t0 = Clock::now();
  EXPECT_TRUE(throttle.Admit(Report(0, 200), t0));
  EXPECT_FALSE(throttle.Admit(Report(99, 200), t0 + milliseconds(19)));
  EXPECT_TRUE(throttle.Admit(Searching(99, 200, 0), t0 + milliseconds(20)));
  EXPECT_FALSE(throttle.Admit(Searching(99, 200, 10), t0 + milliseconds(25)));
  // Too soon after the last record: dropped, and the next report without a step is kept instead.
  EXPECT_FALSE(throttle.Admit(Report(100, 200), t0 + milliseconds(30)));
  EXPECT_TRUE(throttle.Admit(Report(101, 200), t0 + milliseconds(40)));
  EXPECT_FALSE(throttle.Admit(Report(120, 200), t0 + milliseconds(100)));
  EXPECT_TRUE(throttle.Admit(Searching(120, 200, 0), t0 + milliseconds(101)));
  // The phase counts too: the job's first report after "loading".
  proto::JobStatus loading;
  loading.set_phase("loading");
  ProgressThrottle fresh(milliseconds(200));
  EXPECT_TRUE(fresh.Admit(loading, t0));
  EXPECT_FALSE(fresh.Admit(Report(0, 200), t0 + milliseconds(19)));
  EXPECT_TRUE(fresh.Admit(Report(1, 200), t0 + milliseconds(20)));
}

}  // namespace
}  // namespace evoslam
