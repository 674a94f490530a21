#ifndef EVOSLAM_COMMON_UTIL_PROGRESS_BAR_H_
#define EVOSLAM_COMMON_UTIL_PROGRESS_BAR_H_

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace evoslam {

// A one-line progress bar on stderr. It draws only when stderr is a terminal and the CI
// environment variable is unset, and only once the work has run for a second, so pipes, logs and
// short runs stay clean. Redraws are throttled to ten per second.
class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total);
  ProgressBar(std::string label, std::size_t total, bool enabled, std::FILE* out);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void Update(std::size_t done);
  void Finish();  // clears the line

  static bool ShouldDraw();  // stderr is a terminal and not under CI

 private:
  void Draw(std::size_t done);

  std::string label_;
  std::size_t total_;
  bool enabled_;
  std::FILE* out_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_PROGRESS_BAR_H_
