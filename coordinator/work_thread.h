#ifndef EVOSLAM_COORDINATOR_WORK_THREAD_H_
#define EVOSLAM_COORDINATOR_WORK_THREAD_H_

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <stop_token>
#include <thread>
#include <utility>

namespace evoslam {

// A thread of its own that does the work handed to it, one piece at a time, in the order handed.
// When the object goes, the piece under way is finished (`handle` may watch the stop token to
// cut it short) and the work still waiting is dropped undone.
template <typename Work>
class WorkThread {
 public:
  using Handle = std::function<void(Work&, const std::stop_token&)>;

  explicit WorkThread(Handle handle)
      : handle_(std::move(handle)), thread_([this](std::stop_token stop) { Loop(stop); }) {}
  WorkThread(const WorkThread&) = delete;
  WorkThread& operator=(const WorkThread&) = delete;

  ~WorkThread() { Stop(); }

  // Ends the thread as the object's going does; work posted after is kept undone. For threads
  // that post to each other: both stop before either goes.
  void Stop() {
    thread_.request_stop();
    if (thread_.joinable()) thread_.join();
  }

  void Post(Work work) {
    {
      std::lock_guard lock(mutex_);
      queue_.push_back(std::move(work));
    }
    wake_.notify_one();
  }

 private:
  void Loop(const std::stop_token& stop) {
    for (;;) {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, stop, [&] { return !queue_.empty(); });
      if (stop.stop_requested()) return;
      Work work = std::move(queue_.front());
      queue_.pop_front();
      lock.unlock();
      handle_(work, stop);
    }
  }

  Handle handle_;
  std::mutex mutex_;  // guards queue_
  std::condition_variable_any wake_;
  std::deque<Work> queue_;
  std::jthread thread_;  // last: it stops before what it uses goes
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_WORK_THREAD_H_
