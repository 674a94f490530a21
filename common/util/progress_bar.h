#ifndef EVOSLAM_COMMON_UTIL_PROGRESS_BAR_H_
#define EVOSLAM_COMMON_UTIL_PROGRESS_BAR_H_

#include <spdlog/logger.h>

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace evoslam {

// The progress of one piece of work, `done` of `total` units (scans), with the step under way
// inside it, if any ("global search 3/10"), shown one of two ways for the whole work: it never
// starts over. On a terminal, one line on stderr, redrawn in place once the work has run for a
// second and at most ten times a second:
//
//   slam  [######.......]  450/910 scans   49%  0:19 elapsed, 0:21 left  · global search 3/10
//
// The bar is as wide as the terminal leaves room for (10 to 30 characters, the same for the
// whole work); a line still too wide loses the time elapsed, then its end. Elsewhere (a pipe, a
// file, or under CI), a line in the log at info level at most every 10 s, the first after 10 s and
// none once the work is done, so that a long run is not silent and a short one adds nothing:
//
//   progress: 450 of 910 scans (49 %), about 21 s left; global search 3/10
//
// The time left is the rate since the first update applied to the units left, shown once 2 % of
// the work left at the first update is done.
class ProgressBar {
 public:
  using Clock = std::chrono::steady_clock;

  enum class Style { kNone, kBar, kLog };
  struct Output {
    Style style = Style::kNone;
    std::FILE* bar = stderr;  // where kBar draws
    // Where kLog writes; null: the default logger at the time of writing.
    std::shared_ptr<spdlog::logger> log;
    // kBar: the line's width at most, in columns; 0: unlimited.
    std::size_t columns = 0;
    std::function<Clock::time_point()> now = [] { return Clock::now(); };
  };
  // kBar on stderr when it is a terminal and the CI environment variable is unset or empty, with
  // the terminal's width; else kLog.
  static Output ForStderr();

  ProgressBar(std::string label, std::string unit, std::size_t total);  // ForStderr()
  ProgressBar(std::string label, std::string unit, std::size_t total, Output output);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // The work stands at `done` units, with `step` under way inside it (empty: none).
  void Update(std::size_t done, std::string_view step = {});
  void Finish();  // clears a bar's line

 private:
  // The estimate of the time left at `now`, when there is one.
  std::optional<Clock::duration> Left(std::size_t done, Clock::time_point now) const;
  std::string BarLine(std::size_t done, std::string_view step, Clock::time_point now) const;
  std::string LogLine(std::size_t done, std::string_view step, Clock::time_point now) const;

  std::string label_, unit_;
  std::size_t total_;
  Output out_;
  std::size_t bar_width_;
  Clock::time_point start_;
  // The first update, from which the rate is measured (a resumed job starts part-way).
  std::optional<std::size_t> first_done_;
  Clock::time_point first_time_{};
  bool drawn_ = false;  // a bar's line is on the terminal
  Clock::time_point last_shown_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_PROGRESS_BAR_H_
