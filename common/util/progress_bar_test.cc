#include "common/util/progress_bar.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <chrono>
#include <memory>
#include <sstream>
#include <string>

#include "common/util/progress_bar_testing.h"

namespace evoslam {
namespace {

using Clock = ProgressBar::Clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

using testing::BarTo;
using testing::FakeClock;
using Captured = testing::CapturedFile;

// A logger that writes "LEVEL message" lines into `out`.
std::shared_ptr<spdlog::logger> LoggerTo(std::ostringstream& out) {
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_st>(out);
  auto logger = std::make_shared<spdlog::logger>("progress-test", sink);
  logger->set_pattern("%l %v");
  logger->set_level(spdlog::level::info);
  return logger;
}

ProgressBar::Output LogTo(std::ostringstream& out, FakeClock& clock) {
  ProgressBar::Output o;
  o.style = ProgressBar::Style::kLog;
  o.log = LoggerTo(out);
  o.now = [&clock] { return clock.now; };
  return o;
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

TEST(ProgressBarTest, NoneWritesNothing) {
  Captured out;
  FakeClock clock;
  std::ostringstream log;
  {
    ProgressBar::Output o = BarTo(out, clock);
    o.style = ProgressBar::Style::kNone;
    o.log = LoggerTo(log);
    ProgressBar bar("job", "scans", 10, o);
    clock.Advance(seconds(60));
    bar.Update(5);
  }
  EXPECT_EQ(out.text(), "");
  EXPECT_EQ(log.str(), "");
}

TEST(ProgressBarTest, DrawsOnlyAfterASecondAndClearsAtTheEnd) {
  Captured out;
  FakeClock clock;
  {
    ProgressBar bar("localize", "scans", 10, BarTo(out, clock));
    bar.Update(1);
    clock.Advance(milliseconds(999));
    bar.Update(2);
    EXPECT_EQ(out.text(), "") << "short runs stay quiet";
    clock.Advance(milliseconds(1));
    bar.Update(3);
    EXPECT_EQ(
        out.line(),
        "localize  [#########.....................]  3/10 scans   30%  0:01 elapsed, 0:04 left");
  }
  const std::string all = out.text();
  EXPECT_EQ(all.substr(all.size() - 4), "\r\033[K") << "the line is cleared";
}

TEST(ProgressBarTest, ThrottlesRedrawsButAlwaysDrawsTheEnd) {
  Captured out;
  FakeClock clock;
  ProgressBar bar("job", "scans", 100, BarTo(out, clock));
  clock.Advance(seconds(2));
  bar.Update(1);
  const std::size_t after_first = out.text().size();
  clock.Advance(milliseconds(99));
  bar.Update(2);  // within 100 ms of the last draw: skipped
  EXPECT_EQ(out.text().size(), after_first);
  bar.Update(100);  // completion is always shown
  EXPECT_NE(out.line().find("100/100 scans  100%"), std::string::npos) << out.line();
  clock.Advance(milliseconds(100));
  bar.Update(3);
  EXPECT_NE(out.line().find(" 3/100 scans"), std::string::npos) << out.line();
}

// The time left is the rate since the first update applied to what is left, once 2 % of the work
// left at the first update is done; the time elapsed runs from the bar's start.
TEST(ProgressBarTest, TheTimeLeftFollowsTheRateSoFar) {
  Captured out;
  FakeClock clock;
  ProgressBar bar("slam", "scans", 1000, BarTo(out, clock));
  clock.Advance(seconds(3));
  bar.Update(0);  // the rate is measured from here
  clock.Advance(seconds(2));
  bar.Update(19);  // under 2 %: no estimate yet
  EXPECT_EQ(out.line(),
            "slam  [..............................]  19/1000 scans    1%  0:05 elapsed");
  clock.Advance(seconds(18));
  bar.Update(400);  // 400 scans in 20 s: the 600 left take 30 s
  EXPECT_EQ(
      out.line(),
      "slam  [############..................]  400/1000 scans   40%  0:23 elapsed, 0:30 left");
  clock.Advance(seconds(3600));
  bar.Update(401);  // 401 in 3620 s: 599 left take 5407 s
  EXPECT_NE(out.line().find("1:00:23 elapsed, 1:30:07 left"), std::string::npos) << out.line();
}

// A job that resumes part-way: its first update is where it starts from, not work done now.
TEST(ProgressBarTest, TheRateStartsAtTheFirstUpdate) {
  Captured out;
  FakeClock clock;
  ProgressBar bar("slam", "scans", 1000, BarTo(out, clock));
  bar.Update(500);
  clock.Advance(seconds(10));
  bar.Update(600);  // 100 in 10 s: 400 left take 40 s
  EXPECT_NE(out.line().find("0:10 elapsed, 0:40 left"), std::string::npos) << out.line();
}

// A step under way is shown inside the job's line, and leaves it when it ends; the bar, the
// counts and the times go on as they were.
TEST(ProgressBarTest, AStepIsShownInsideTheLineAndNeverResetsIt) {
  Captured out;
  FakeClock clock;
  ProgressBar bar("slam", "scans", 910, BarTo(out, clock));
  bar.Update(0);
  clock.Advance(seconds(19));
  bar.Update(450, "global search 3/10");
  EXPECT_EQ(
      out.line(),
      "slam  [##############................]  450/910 scans   49%  0:19 elapsed, 0:19 left  · "
      "global search 3/10");
  clock.Advance(seconds(1));
  bar.Update(450, "global search 10/10");
  EXPECT_NE(out.line().find("450/910 scans   49%  0:20 elapsed, 0:20 left  · global search 10/10"),
            std::string::npos)
      << out.line();
  clock.Advance(seconds(1));
  bar.Update(451);
  EXPECT_EQ(out.line().find("global search"), std::string::npos) << out.line();
  EXPECT_NE(out.line().find("451/910 scans   49%  0:21 elapsed"), std::string::npos) << out.line();
  // Each draw clears what a longer line before it left.
  EXPECT_EQ(Count(out.text(), "\r"), Count(out.text(), "\033[K"));
}

// The bar takes the room the terminal leaves, the same for the whole work; a line still too wide
// loses the time elapsed, then its end, by characters.
TEST(ProgressBarTest, ALineFitsTheTerminal) {
  Captured wide_out, narrow_out, tiny_out;
  FakeClock clock;
  ProgressBar wide("slam", "scans", 910, BarTo(wide_out, clock, 200));
  ProgressBar middle("slam", "scans", 910, BarTo(wide_out, clock, 100));
  ProgressBar narrow("slam", "scans", 910, BarTo(narrow_out, clock, 80));
  ProgressBar tiny("slam", "scans", 910, BarTo(tiny_out, clock, 39));
  for (ProgressBar* bar : {&wide, &middle, &narrow, &tiny}) bar->Update(0);
  clock.Advance(seconds(2));
  wide.Update(450, "global search 3/10");
  EXPECT_EQ(
      wide_out.line(),
      "slam  [##############................]  450/910 scans   49%  0:02 elapsed, 0:02 left  · "
      "global search 3/10");
  middle.Update(450, "global search 3/10");
  EXPECT_EQ(wide_out.line(),
            "slam  [########..........]  450/910 scans   49%  0:02 elapsed, 0:02 left  · "
            "global search 3/10");
  clock.Advance(milliseconds(100));
  middle.Update(451);  // the same bar without the step
  EXPECT_EQ(wide_out.line(),
            "slam  [########..........]  451/910 scans   49%  0:02 elapsed, 0:02 left");
  narrow.Update(450, "global search 3/10");
  EXPECT_EQ(narrow_out.line(),
            "slam  [####......]  450/910 scans   49%  0:02 left  · global search 3/10");
  tiny.Update(450, "global search 3/10");
  EXPECT_EQ(tiny_out.line(), "slam  [####......]  450/910 scans   49%");
}

// Without a terminal: a log line at info level at most every 10 s, the first after 10 s.
TEST(ProgressBarTest, WithoutATerminalALogLineAtMostEveryTenSeconds) {
  std::ostringstream log;
  FakeClock clock;
  {
    ProgressBar bar("slam", "scans", 910, LogTo(log, clock));
    bar.Update(0);
    for (int k = 1; k <= 99; ++k) {
      clock.Advance(milliseconds(100));
      bar.Update(static_cast<std::size_t>(k));
    }
    EXPECT_EQ(log.str(), "") << "nothing in the first 10 s";
    clock.Advance(milliseconds(100));
    bar.Update(100);
    EXPECT_EQ(log.str(), "info progress: 100 of 910 scans (10 %), about 1 min 21 s left\n");
    // Updates every 250 ms for 30 s more: a line at 20 s, 30 s and 40 s, none in between.
    for (int k = 1; k <= 120; ++k) {
      clock.Advance(milliseconds(250));
      bar.Update(100 + static_cast<std::size_t>(k), k > 110 ? "global search 3/10" : "");
    }
    EXPECT_EQ(Count(log.str(), "\n"), 4u) << log.str();
    EXPECT_EQ(Count(log.str(), "progress: "), 4u) << log.str();
    EXPECT_NE(log.str().find("info progress: 220 of 910 scans (24 %), about 2 min 5 s left; "
                             "global search 3/10\n"),
              std::string::npos)
        << log.str();
    clock.Advance(seconds(20));
    bar.Update(910);
  }
  EXPECT_EQ(Count(log.str(), "\n"), 4u) << "nothing for the work done, nor at the end";
}

TEST(ProgressBarTest, WithoutATerminalAShortRunSaysNothing) {
  std::ostringstream log;
  FakeClock clock;
  ProgressBar bar("slam", "scans", 300, LogTo(log, clock));
  for (std::size_t k = 0; k <= 300; ++k) {
    bar.Update(k);
    clock.Advance(milliseconds(33));
  }
  EXPECT_EQ(log.str(), "");
}

// The log's level decides: at warn the lines are gone.
TEST(ProgressBarTest, TheLogLevelSilencesTheLines) {
  std::ostringstream log;
  FakeClock clock;
  ProgressBar::Output o = LogTo(log, clock);
  o.log->set_level(spdlog::level::warn);
  ProgressBar bar("slam", "scans", 100, o);
  for (std::size_t k = 0; k <= 100; ++k) {
    bar.Update(k);
    clock.Advance(seconds(1));
  }
  EXPECT_EQ(log.str(), "");
}

TEST(ProgressBarTest, QuietUnderCi) {
  const char* before = std::getenv("CI");
  const std::string saved = before ? before : "";
  ::setenv("CI", "true", 1);
  EXPECT_EQ(ProgressBar::ForStderr().style, ProgressBar::Style::kLog);
  if (before) {
    ::setenv("CI", saved.c_str(), 1);
  } else {
    ::unsetenv("CI");
  }
}

}  // namespace
}  // namespace evoslam
