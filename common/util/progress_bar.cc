#include "common/util/progress_bar.h"

#include <spdlog/spdlog.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace evoslam {
namespace {

using Seconds = std::chrono::duration<double>;

constexpr auto kFirstDraw = std::chrono::seconds(1);
constexpr auto kRedraw = std::chrono::milliseconds(100);
constexpr auto kLogEvery = std::chrono::seconds(10);
constexpr std::size_t kWidestBar = 30;
constexpr std::size_t kNarrowestBar = 10;
// What a bar's line leaves for a step: "  · global search 100/100" and a little more.
constexpr std::size_t kStepRoom = 26;

long long WholeSeconds(ProgressBar::Clock::duration d) {
  return std::max(0LL, static_cast<long long>(Seconds(d).count() + 0.5));
}

// 0:21, 12:05, 1:02:03.
std::string ClockTime(ProgressBar::Clock::duration d) {
  const long long s = WholeSeconds(d);
  char text[32];
  if (s < 3600) {
    std::snprintf(text, sizeof text, "%lld:%02lld", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  }
  return text;
}

// 21 s, 3 min 20 s, 1 h 2 min.
std::string Words(ProgressBar::Clock::duration d) {
  const long long s = WholeSeconds(d);
  if (s < 60) return std::to_string(s) + " s";
  if (s < 3600) return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string(s / 60 % 60) + " min";
}

// Columns the UTF-8 text takes, a column a character.
std::size_t Columns(std::string_view text) {
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// The text's first `columns` characters.
std::string FirstColumns(std::string_view text, std::size_t columns) {
  std::size_t seen = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((text[i] & 0xC0) != 0x80 && seen++ == columns) return std::string(text.substr(0, i));
  }
  return std::string(text);
}

// The bar's width for a terminal `columns` wide (0: unlimited): what the rest of the line leaves at
// its widest, with a step, within bounds. It stays the same while the line's text changes.
std::size_t BarWidth(std::string_view label, std::string_view unit, std::size_t total,
                     std::size_t columns) {
  if (columns == 0) return kWidestBar;
  const std::size_t rest = Columns(label) + 6 + 2 * std::to_string(total).size() + 2 +
                           Columns(unit) + 6 + Columns("  99:59 elapsed, 99:59 left") + kStepRoom;
  return std::clamp(columns > rest ? columns - rest : 0, kNarrowestBar, kWidestBar);
}

}  // namespace

ProgressBar::Output ProgressBar::ForStderr() {
  Output out;
  const char* ci = std::getenv("CI");
  const bool terminal = isatty(fileno(stderr)) && (ci == nullptr || *ci == '\0');
  out.style = terminal ? Style::kBar : Style::kLog;
  winsize size{};
  if (terminal && ioctl(fileno(stderr), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) {
    // The last column left free: a line that fills it wraps on some terminals.
    out.columns = size.ws_col - 1u;
  }
  return out;
}

ProgressBar::ProgressBar(std::string label, std::string unit, std::size_t total)
    : ProgressBar(std::move(label), std::move(unit), total, ForStderr()) {}

ProgressBar::ProgressBar(std::string label, std::string unit, std::size_t total, Output output)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      out_(std::move(output)),
      bar_width_(BarWidth(label_, unit_, total_, out_.columns)),
      start_(out_.now()),
      last_shown_(start_) {}

ProgressBar::~ProgressBar() { Finish(); }

void ProgressBar::Update(std::size_t done, std::string_view step) {
  if (out_.style == Style::kNone) return;
  done = std::min(done, total_);
  const Clock::time_point now = out_.now();
  if (!first_done_) {
    first_done_ = done;
    first_time_ = now;
  }
  if (out_.style == Style::kLog) {
    // Work done needs no line: what it made follows.
    if (done == total_ || now - last_shown_ < kLogEvery) return;
    last_shown_ = now;
    const std::string line = LogLine(done, step, now);
    if (out_.log) {
      out_.log->info("{}", line);
    } else {
      spdlog::info("{}", line);
    }
    return;
  }
  if (now - start_ < kFirstDraw) return;
  if (drawn_ && now - last_shown_ < kRedraw && done < total_) return;
  last_shown_ = now;
  std::fprintf(out_.bar, "\r%s\033[K", BarLine(done, step, now).c_str());
  std::fflush(out_.bar);
  drawn_ = true;
}

std::optional<ProgressBar::Clock::duration> ProgressBar::Left(std::size_t done,
                                                              Clock::time_point now) const {
  if (!first_done_ || done <= *first_done_) return std::nullopt;
  const std::size_t advanced = done - *first_done_;
  if (advanced * 50 < total_ - *first_done_) return std::nullopt;
  const Seconds per_unit = Seconds(now - first_time_) / static_cast<double>(advanced);
  return std::chrono::duration_cast<Clock::duration>(per_unit * static_cast<double>(total_ - done));
}

std::string ProgressBar::BarLine(std::size_t done, std::string_view step,
                                 Clock::time_point now) const {
  const std::size_t percent = total_ > 0 ? done * 100 / total_ : 100;
  const std::size_t filled = total_ > 0 ? done * bar_width_ / total_ : bar_width_;
  const std::string counts = label_ + "  [" + std::string(filled, '#') +
                             std::string(bar_width_ - filled, '.') + "]  " + std::to_string(done) +
                             "/" + std::to_string(total_) + " " + unit_ + "  " +
                             (percent < 10    ? "  "
                              : percent < 100 ? " "
                                              : "") +
                             std::to_string(percent) + "%";
  const std::optional<Clock::duration> left = Left(done, now);
  const std::string left_text = left ? ClockTime(*left) + " left" : "";
  const std::string step_text = step.empty() ? "" : "  · " + std::string(step);
  std::string line = counts + "  " + ClockTime(now - start_) + " elapsed" +
                     (left ? ", " + left_text : "") + step_text;
  if (out_.columns == 0 || Columns(line) <= out_.columns) return line;
  // Too wide for the terminal: without the time elapsed, then cut.
  line = counts + (left ? "  " + left_text : "") + step_text;
  return FirstColumns(line, out_.columns);
}

std::string ProgressBar::LogLine(std::size_t done, std::string_view step,
                                 Clock::time_point now) const {
  const std::size_t percent = total_ > 0 ? done * 100 / total_ : 100;
  std::string line = "progress: " + std::to_string(done) + " of " + std::to_string(total_) + " " +
                     unit_ + " (" + std::to_string(percent) + " %)";
  if (const auto left = Left(done, now)) line += ", about " + Words(*left) + " left";
  if (!step.empty()) line += "; " + std::string(step);
  return line;
}

void ProgressBar::Finish() {
  if (!drawn_) return;
  std::fprintf(out_.bar, "\r\033[K");
  std::fflush(out_.bar);
  drawn_ = false;
}

}  // namespace evoslam
