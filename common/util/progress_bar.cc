#include "common/util/progress_bar.h"

#include <unistd.h>

#include <cstdlib>
#include <utility>

namespace evoslam {

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : ProgressBar(std::move(label), total, ShouldDraw(), stderr) {}

ProgressBar::ProgressBar(std::string label, std::size_t total, bool enabled, std::FILE* out)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      out_(out),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { Finish(); }

bool ProgressBar::ShouldDraw() {
  const char* ci = std::getenv("CI");
  return isatty(fileno(stderr)) && (ci == nullptr || *ci == '\0');
}

void ProgressBar::Update(std::size_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < std::chrono::seconds(1)) return;
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100) && done < total_) return;
  last_draw_ = now;
  Draw(done);
}

void ProgressBar::Draw(std::size_t done) {
  constexpr int kWidth = 30;
  const double fraction =
      total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  const int filled = static_cast<int>(fraction * kWidth);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '.');
  std::fprintf(out_, "\r%s [%s] %zu/%zu %3.0f%%  %.1fs elapsed, %.1fs left ", label_.c_str(),
               bar.c_str(), done, total_, 100.0 * fraction, elapsed, eta);
  std::fflush(out_);
  drawn_ = true;
}

void ProgressBar::Finish() {
  if (!drawn_) return;
  std::fprintf(out_, "\r\033[K");
  std::fflush(out_);
  drawn_ = false;
}

}  // namespace evoslam
