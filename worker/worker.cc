#include "worker/worker.h"

#include <omp.h>
#include <spdlog/spdlog.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "common/protocol/wire.h"
#include "common/protocol/zmq_io.h"
#include "common/service/dataset_files.h"
#include "common/util/counted.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"
#include "worker/task_executor.h"

namespace evoslam {
namespace {

using Clock = std::chrono::steady_clock;

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// 128 random bits, drawn once per worker: how the coordinator knows it again on a new connection.
std::string NewInstance() {
  std::random_device random;
  std::string hex;
  for (int i = 0; i < 4; ++i) hex += fmt::format("{:08x}", random());
  return hex;
}

std::string HostName() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

// The thread tasks are computed on, one at a time, while the worker's loop keeps talking. It
// lives as long as the worker, so its OpenMP team is made once, not once per task. It owns
// everything it touches, so a stopping worker can leave it behind mid-task.
class ComputeThread {
 public:
  ComputeThread(std::shared_ptr<TaskExecutor> executor, int threads)
      : state_(std::make_shared<State>()) {
    state_->fd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (state_->fd < 0) throw Error("cannot create an eventfd");
    thread_ = std::thread([state = state_, executor = std::move(executor), threads] {
      if (threads > 0) omp_set_num_threads(threads);
      for (;;) {
        proto::Task task;
        {
          std::unique_lock lock(state->mutex);
          state->wake.wait(lock, [&] { return state->task.has_value() || state->quit; });
          if (state->quit) return;
          task = std::move(*state->task);
          state->task.reset();
        }
        proto::TaskResult result = executor->Run(task);
        {
          std::lock_guard lock(state->mutex);
          state->result = std::move(result);
        }
        const std::uint64_t one = 1;
        [[maybe_unused]] const auto n = ::write(state->fd, &one, sizeof one);
      }
    });
  }
  ~ComputeThread() {
    {
      std::lock_guard lock(state_->mutex);
      state_->quit = true;
    }
    state_->wake.notify_one();
    if (thread_.joinable()) thread_.join();
  }
  ComputeThread(const ComputeThread&) = delete;
  ComputeThread& operator=(const ComputeThread&) = delete;

  void Start(proto::Task task) {
    {
      std::lock_guard lock(state_->mutex);
      state_->task = std::move(task);
    }
    state_->wake.notify_one();
  }
  // Readable when a result is waiting.
  int fd() const { return state_->fd; }
  std::optional<proto::TaskResult> Result() {
    std::uint64_t count = 0;
    [[maybe_unused]] const auto n = ::read(state_->fd, &count, sizeof count);
    std::lock_guard lock(state_->mutex);
    return std::exchange(state_->result, std::nullopt);
  }
  // Leaves the thread to finish its task on its own; only for a process about to end.
  void Abandon() {
    {
      std::lock_guard lock(state_->mutex);
      state_->quit = true;
    }
    thread_.detach();
  }

 private:
  struct State {
    ~State() {
      if (fd >= 0) ::close(fd);
    }
    std::mutex mutex;
    std::condition_variable wake;
    std::optional<proto::Task> task;
    std::optional<proto::TaskResult> result;
    bool quit = false;
    int fd = -1;
  };
  std::shared_ptr<State> state_;
  std::thread thread_;
};

}  // namespace

class Worker::Impl {
 public:
  Impl(zmq::context_t& context, WorkerOptions options);
  bool Run(const std::stop_token& stop);

 private:
  void OpenSocket();
  void Connect();
  void Send(const proto::WorkerMessage& message);
  void SendReady();
  void OnMessage(const proto::CoordinatorMessage& message);
  void StartIfReady();
  void Finish(proto::TaskResult result);

  zmq::context_t& context_;
  WorkerOptions options_;
  spdlog::level::level_enum notice_;
  const std::string instance_ = NewInstance();
  std::optional<TempDir> private_cache_;
  std::shared_ptr<DatasetFiles> files_;
  std::shared_ptr<TaskExecutor> executor_;
  std::optional<zmq::socket_t> socket_;

  std::optional<proto::Task> task_;  // the task in hand
  std::vector<proto::DatasetRef> fetching_;
  std::unique_ptr<ComputeThread> compute_;
  bool computing_ = false;
  bool discard_ = false;  // the coordinator gave the task in hand to another worker
  bool ready_owed_ = false;
};

Worker::Impl::Impl(zmq::context_t& context, WorkerOptions options)
    : context_(context),
      options_(std::move(options)),
      notice_(options_.quiet ? spdlog::level::debug : spdlog::level::info) {
  if (options_.hostname.empty()) options_.hostname = HostName();
  if (options_.cache_dir.empty()) {
    private_cache_.emplace("evoslam-worker");
    options_.cache_dir = private_cache_->path();
  }
  files_ = std::make_shared<DatasetFiles>(options_.cache_dir);
  executor_ = std::make_shared<TaskExecutor>(files_);
  compute_ = std::make_unique<ComputeThread>(executor_, options_.threads);
}

void Worker::Impl::OpenSocket() {
  socket_.emplace(context_, zmq::socket_type::dealer);
  socket_->set(zmq::sockopt::linger, 1000);  // time to deliver a goodbye
  // With no connection up (the coordinator gone, or refusing our key) a send would block for
  // ever; it gives up instead, and the heartbeats decide what to do.
  socket_->set(zmq::sockopt::sndtimeo,
               static_cast<int>(std::max(1.0, 1000.0 * options_.heartbeat_seconds)));
  if (options_.curve) MakeCurveClient(*socket_, *options_.curve);
  evoslam::Connect(*socket_, options_.endpoint, "the coordinator");
}

void Worker::Impl::Connect() {
  OpenSocket();
  SendReady();
}

void Worker::Impl::Send(const proto::WorkerMessage& message) {
  if (!evoslam::Send(*socket_, Encode(message))) {
    spdlog::debug("could not reach the coordinator at {}; message dropped", options_.endpoint);
  }
}

void Worker::Impl::SendReady() {
  proto::WorkerMessage m;
  m.mutable_ready()->set_hostname(options_.hostname);
  m.mutable_ready()->set_instance(instance_);
  m.mutable_ready()->set_threads(
      static_cast<std::uint32_t>(options_.threads > 0 ? options_.threads : omp_get_max_threads()));
  Send(m);
  ready_owed_ = false;
}

void Worker::Impl::StartIfReady() {
  if (!task_ || computing_ || !fetching_.empty()) return;
  compute_->Start(*task_);
  computing_ = true;
}

void Worker::Impl::Finish(proto::TaskResult result) {
  if (!discard_) {
    proto::WorkerMessage m;
    *m.mutable_result() = std::move(result);
    Send(m);
  }
  task_.reset();
  fetching_.clear();
  computing_ = false;
  discard_ = false;
  if (ready_owed_) SendReady();
}

void Worker::Impl::OnMessage(const proto::CoordinatorMessage& message) {
  switch (message.message_case()) {
    case proto::CoordinatorMessage::kTask: {
      if (task_) {
        spdlog::warn("the coordinator sent task {} while {} is in hand; refused",
                     message.task().task_id(), task_->task_id());
        proto::WorkerMessage m;
        m.mutable_result()->set_task_id(message.task().task_id());
        m.mutable_result()->mutable_error()->set_code(proto::ERROR_CODE_QUEUE_FULL);
        m.mutable_result()->mutable_error()->set_message("worker busy");
        Send(m);
        return;
      }
      task_ = message.task();
      spdlog::debug("task {} of {}", task_->task_id(), task_->job_id());
      fetching_ = executor_->Missing(*task_);
      for (const proto::DatasetRef& ref : fetching_) {
        spdlog::log(notice_, "fetching dataset {} ({})", ref.name(), ref.sha256());
        proto::WorkerMessage m;
        m.mutable_fetch()->set_sha256(ref.sha256());
        Send(m);
      }
      StartIfReady();
      return;
    }
    case proto::CoordinatorMessage::kDataset: {
      const proto::DatasetContent& content = message.dataset();
      const auto it = std::find_if(fetching_.begin(), fetching_.end(), [&](const auto& ref) {
        return ref.sha256() == content.dataset().sha256();
      });
      if (it == fetching_.end()) return;
      proto::TaskResult failed;
      failed.set_task_id(task_->task_id());
      if (content.content().empty() && it->size_bytes() != 0) {
        failed.mutable_error()->set_message("the coordinator does not have dataset " + it->name());
        Finish(std::move(failed));
        return;
      }
      try {
        files_->Put(*it, content.content());
      } catch (const std::exception& e) {
        // This worker's cache, not the task: another worker may run it.
        spdlog::error("cannot cache dataset {}: {}", it->name(), e.what());
        failed.mutable_error()->set_message("worker " + options_.hostname +
                                            " cannot cache dataset " + it->name() + ": " +
                                            e.what());
        failed.set_worker_fault(true);
        Finish(std::move(failed));
        return;
      }
      fetching_.erase(it);
      StartIfReady();
      return;
    }
    case proto::CoordinatorMessage::kDisconnect:
      spdlog::log(notice_, "the coordinator asks for a new start: {}",
                  message.disconnect().reason().substr(0, 200));
      if (task_) {
        discard_ = true;  // already given to another worker
        ready_owed_ = true;
        if (!computing_) Finish({});
      } else {
        SendReady();
      }
      return;
    default:
      return;  // heartbeats only prove the coordinator alive
  }
}

bool Worker::Impl::Run(const std::stop_token& stop) {
  Connect();
  spdlog::log(notice_, "worker: connecting to {} ({}, cache {})", options_.endpoint,
              Counted(options_.threads > 0 ? options_.threads : omp_get_max_threads(), "thread"),
              options_.cache_dir.string());
  const WireLimits limits;
  int liveness = options_.liveness;
  double backoff = options_.first_backoff_seconds;
  Clock::time_point next_heartbeat = Clock::now() + Seconds(options_.heartbeat_seconds);
  Clock::time_point heard = Clock::now();
  std::optional<Clock::time_point> leaving_by;
  for (;;) {
    if (stop.stop_requested() && !leaving_by) {
      leaving_by = Clock::now() + Seconds(options_.grace_seconds);
      if (task_) spdlog::log(notice_, "stopping: finishing task {} first", task_->task_id());
    }
    if (leaving_by && (!task_ || Clock::now() >= *leaving_by)) break;

    std::vector<zmq::pollitem_t> items = {{socket_->handle(), 0, ZMQ_POLLIN, 0}};
    if (computing_) items.push_back({nullptr, compute_->fd(), ZMQ_POLLIN, 0});
    zmq::poll(items, std::chrono::milliseconds(100));

    if (items[0].revents & ZMQ_POLLIN) {
      while (auto frames = ReceiveFrames(*socket_)) {
        liveness = options_.liveness;
        heard = Clock::now();
        backoff = options_.first_backoff_seconds;
        if (frames->size() != 1) {
          spdlog::warn("dropped a message of {} frames from the coordinator", frames->size());
          continue;
        }
        try {
          OnMessage(DecodeCoordinatorMessage(Bytes(frames->front()), limits));
        } catch (const ProtocolError& e) {
          spdlog::warn("dropped a message from the coordinator: {}", e.what());
        }
      }
    }
    if (computing_ && items.size() > 1 && (items[1].revents & ZMQ_POLLIN)) {
      if (auto result = compute_->Result()) Finish(std::move(*result));
    }
    const Clock::time_point now = Clock::now();
    if (now - heard > Seconds(options_.heartbeat_seconds)) {
      heard = now;
      if (--liveness <= 0) {
        spdlog::warn("no word from the coordinator at {}; reconnecting in {:.0f} s",
                     options_.endpoint, backoff);
        // Whatever is in hand has been given to another worker by now.
        if (task_) {
          discard_ = true;
          if (!computing_) Finish({});
        }
        socket_.reset();
        const Clock::time_point until = now + Seconds(backoff);
        while (Clock::now() < until && !stop.stop_requested())
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
        backoff = std::min(backoff * 2, options_.max_backoff_seconds);
        if (computing_) {
          ready_owed_ = true;
          OpenSocket();
        } else {
          Connect();
        }
        liveness = options_.liveness;
        heard = Clock::now();
      }
    }
    if (now >= next_heartbeat) {
      proto::WorkerMessage beat;
      beat.mutable_heartbeat();
      Send(beat);
      next_heartbeat = now + Seconds(options_.heartbeat_seconds);
    }
  }

  proto::WorkerMessage bye;
  bye.mutable_disconnect()->set_reason("worker stopping");
  bool clean = true;
  if (task_ && !discard_) {
    bye.mutable_disconnect()->set_handed_back_task_id(task_->task_id());
    spdlog::log(notice_, "stopping: handing task {} back", task_->task_id());
  }
  if (computing_) {
    compute_->Abandon();
    clean = false;
  }
  Send(bye);
  spdlog::log(notice_, "worker: left {}", options_.endpoint);
  return clean;
}

Worker::Worker(zmq::context_t& context, WorkerOptions options)
    : impl_(std::make_unique<Impl>(context, std::move(options))) {}
Worker::~Worker() = default;
bool Worker::Run(std::stop_token stop) { return impl_->Run(stop); }

}  // namespace evoslam
