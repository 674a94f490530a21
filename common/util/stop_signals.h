#ifndef EVOSLAM_COMMON_UTIL_STOP_SIGNALS_H_
#define EVOSLAM_COMMON_UTIL_STOP_SIGNALS_H_

#include <atomic>
#include <stop_token>
#include <thread>

namespace evoslam {

// Turns SIGINT and SIGTERM into a stop request that long-running loops poll. The signals are
// blocked in every thread and taken by one waiting thread, so no handler runs at an arbitrary
// point of the program. Create it first in main, before any other thread exists, so that every
// thread inherits the blocked signals.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  std::stop_token token() const { return source_.get_token(); }
  // The signal that asked to stop, or 0.
  int signal() const { return signal_; }

 private:
  std::stop_source source_;
  std::atomic<int> signal_{0};
  std::jthread waiter_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_STOP_SIGNALS_H_
