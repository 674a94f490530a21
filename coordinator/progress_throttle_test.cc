#include "coordinator/progress_throttle.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace evoslam {
namespace {

using Clock = ProgressThrottle::Clock;
using std::chrono::milliseconds;

proto::JobStatus Report(const std::string& phase, std::uint64_t done, std::uint64_t total) {
  proto::JobStatus s;
  s.set_phase(phase);
  s.set_done(done);
  s.set_total(total);
  return s;
}

TEST(ProgressThrottleTest, WithinAPhaseOneReportPerIntervalAndTheLastAreKept) {
  ProgressThrottle throttle(milliseconds(200));
  const Clock::time_point t0 = Clock::now();
  EXPECT_TRUE(throttle.Admit(Report("local search", 1, 100), t0));
  EXPECT_FALSE(throttle.Admit(Report("local search", 2, 100), t0 + milliseconds(10)));
  EXPECT_FALSE(throttle.Admit(Report("local search", 40, 100), t0 + milliseconds(199)));
  EXPECT_TRUE(throttle.Admit(Report("local search", 41, 100), t0 + milliseconds(200)));
  // The interval runs from the last report kept, not from the last one offered.
  EXPECT_FALSE(throttle.Admit(Report("local search", 42, 100), t0 + milliseconds(390)));
  EXPECT_TRUE(throttle.Admit(Report("local search", 43, 100), t0 + milliseconds(400)));
  EXPECT_TRUE(throttle.Admit(Report("local search", 100, 100), t0 + milliseconds(401)));
}

// Local search, a global search, a short stretch of local search and another global search, each
// far shorter than the interval: each shows once a tenth of the interval has passed since the last
// record.
TEST(ProgressThrottleTest, ANewPhaseShowsAfterATenthOfTheInterval) {
  ProgressThrottle throttle(milliseconds(200));
  const Clock::time_point t0 = Clock::now();
  EXPECT_TRUE(throttle.Admit(Report("local search", 0, 200), t0));
  EXPECT_FALSE(throttle.Admit(Report("local search", 99, 200), t0 + milliseconds(19)));
  EXPECT_TRUE(throttle.Admit(Report("global search", 0, 20), t0 + milliseconds(20)));
  EXPECT_FALSE(throttle.Admit(Report("global search", 10, 20), t0 + milliseconds(25)));
  // Too soon after the last record: dropped, and the next report of the phase is kept instead.
  EXPECT_FALSE(throttle.Admit(Report("local search", 101, 200), t0 + milliseconds(30)));
  EXPECT_TRUE(throttle.Admit(Report("local search", 102, 200), t0 + milliseconds(40)));
  EXPECT_FALSE(throttle.Admit(Report("local search", 120, 200), t0 + milliseconds(100)));
  EXPECT_TRUE(throttle.Admit(Report("global search", 0, 20), t0 + milliseconds(101)));
}

}  // namespace
}  // namespace evoslam
