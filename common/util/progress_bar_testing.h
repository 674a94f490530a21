#ifndef EVOSLAM_COMMON_UTIL_PROGRESS_BAR_TESTING_H_
#define EVOSLAM_COMMON_UTIL_PROGRESS_BAR_TESTING_H_

// For tests: what a progress bar draws, on a clock that moves only when the test moves it.

#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/util/progress_bar.h"

namespace evoslam::testing {

// Collects what a bar writes, through a POSIX memory stream.
class CapturedFile {
 public:
  CapturedFile() : file_(open_memstream(&data_, &size_)) {}
  ~CapturedFile() {
    std::fclose(file_);
    std::free(data_);
  }
  CapturedFile(const CapturedFile&) = delete;
  CapturedFile& operator=(const CapturedFile&) = delete;

  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    return std::string(data_, size_);
  }
  // The line last drawn: what follows the last carriage return, up to the clearing of the rest
  // of the line.
  std::string line() {
    std::string t = text();
    t = t.substr(t.rfind('\r') + 1);
    return t.substr(0, t.find("\033[K"));
  }

 private:
  char* data_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* file_;
};

// Time that passes only when a test says so.
struct FakeClock {
  ProgressBar::Clock::time_point now = ProgressBar::Clock::time_point(std::chrono::seconds(1000));
  void Advance(ProgressBar::Clock::duration d) { now += d; }
};

// A terminal's bar drawn into `out`, `columns` wide (0: unlimited), on `clock`.
inline ProgressBar::Output BarTo(CapturedFile& out, FakeClock& clock, std::size_t columns = 0) {
  ProgressBar::Output o;
  o.style = ProgressBar::Style::kBar;
  o.bar = out.file();
  o.columns = columns;
  o.now = [&clock] { return clock.now; };
  return o;
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_UTIL_PROGRESS_BAR_TESTING_H_
