#include "common/util/stop_signals.h"

#include <pthread.h>
#include <signal.h>

#include <ctime>

namespace evoslam {
namespace {

sigset_t StopSet() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

}  // namespace

StopSignals::StopSignals() {
  const sigset_t set = StopSet();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  waiter_ = std::jthread([this](std::stop_token own) {
    const sigset_t wanted = StopSet();
    const timespec tick{0, 100'000'000};
    while (!own.stop_requested()) {
      const int sig = sigtimedwait(&wanted, nullptr, &tick);
      if (sig > 0) {
        signal_ = sig;
        source_.request_stop();
      }
    }
  });
}

StopSignals::~StopSignals() {
  waiter_.request_stop();
  waiter_.join();
  const sigset_t set = StopSet();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

}  // namespace evoslam
