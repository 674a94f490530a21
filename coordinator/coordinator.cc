#include "coordinator/coordinator.h"

#include <omp.h>
#include <spdlog/spdlog.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include "common/protocol/wire.h"
#include "common/protocol/zmq_io.h"
#include "common/service/dataset_files.h"
#include "common/service/job_state.h"
#include "common/util/counted.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"
#include "coordinator/job_context.h"
#include "coordinator/job_kinds.h"
#include "coordinator/job_store.h"
#include "coordinator/metrics.h"
#include "coordinator/metrics_server.h"
#include "coordinator/progress_throttle.h"
#include "coordinator/task_board.h"
#include "coordinator/upload_assembler.h"
#include "coordinator/upload_intake.h"
#include "coordinator/upload_table.h"
#include "coordinator/worker_table.h"
#include "coordinator/zap_handler.h"

namespace evoslam {
namespace {

using Clock = std::chrono::steady_clock;

double UnixNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// The printable start of a socket identity, for logs.
std::string Peer(const std::string& identity) {
  std::string hex;
  for (unsigned char c : identity.substr(0, 8)) {
    constexpr const char* kDigits = "0123456789abcdef";
    hex += kDigits[c >> 4];
    hex += kDigits[c & 15];
  }
  return hex;
}

// An eventfd the job threads write to so that the broker's poll wakes up.
class Waker {
 public:
  Waker() : fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
    if (fd_ < 0) throw Error("cannot create an eventfd");
  }
  ~Waker() { ::close(fd_); }
  Waker(const Waker&) = delete;
  Waker& operator=(const Waker&) = delete;
  void Wake() const {
    const std::uint64_t one = 1;
    [[maybe_unused]] const auto n = ::write(fd_, &one, sizeof one);
  }
  void Drain() const {
    std::uint64_t count = 0;
    [[maybe_unused]] const auto n = ::read(fd_, &count, sizeof count);
  }
  int fd() const { return fd_; }

 private:
  int fd_;
};

proto::DatasetRef Ref(const std::string& sha256) {
  proto::DatasetRef ref;
  ref.set_sha256(sha256);
  return ref;
}

struct Watcher {
  std::string identity;
  std::uint64_t request_id = 0;
};

// Who sent a request: the client's CURVE public key (ZAP's User-Id), "" with CURVE off, when
// every client is the one owner of every job.
struct Requester {
  std::string key;
  bool admin = false;  // sees every job
  bool Sees(const std::string& owner) const { return admin || owner == key; }
};

// The User-Id ZAP gave the connection a frame came on: the peer's public key. (zmq_msg_gets
// takes a mutable message.)
std::string UserId(zmq::message_t& frame) {
  try {
    return frame.gets("User-Id");
  } catch (const zmq::error_t&) {
    return {};  // no ZAP handler answered for this connection
  }
}

// A submit id is the client's to choose, but it is logged and stored: printable and short.
void CheckSubmitId(const std::string& id) {
  constexpr std::size_t kMaxSubmitId = 128;
  const bool printable =
      std::all_of(id.begin(), id.end(), [](char c) { return c > ' ' && c < 127; });
  if (id.size() > kMaxSubmitId || !printable) {
    throw ProtocolError(proto::ERROR_CODE_INVALID,
                        "a submit id is up to " + std::to_string(kMaxSubmitId) +
                            " printable ASCII characters without spaces");
  }
}

}  // namespace

class Coordinator::Impl {
 public:
  Impl(zmq::context_t& context, CoordinatorOptions options);
  ~Impl();
  void Run(const std::stop_token& stop);

  std::string clients_endpoint() const { return clients_.get(zmq::sockopt::last_endpoint); }
  std::string workers_endpoint() const { return workers_.get(zmq::sockopt::last_endpoint); }
  std::string metrics_url() const { return metrics_server_ ? metrics_server_->url() : ""; }

 private:
  // Broker thread.
  void OnClientFrames();
  void OnWorkerFrames();
  // The reply to a request; none yet for one handed to the upload intake, which answers it.
  std::optional<proto::ClientReply> Handle(const std::string& identity, const Requester& requester,
                                           proto::ClientRequest& request);
  void Upload(const std::string& identity, const proto::ClientRequest& request,
              const Requester& requester);
  void Chunk(const std::string& identity, proto::ClientRequest& request,
             const Requester& requester);
  void SendUploadAnswers();
  void DropSilentUploads(Clock::time_point now);
  proto::ClientReply Submit(const proto::SubmitJob& submit, const Requester& requester);
  proto::ClientReply Watch(const std::string& identity, const Requester& requester,
                           const proto::ClientRequest& request);
  proto::ClientReply Result(const std::string& job_id, const Requester& requester);
  proto::ClientReply Cancel(const std::string& job_id, const Requester& requester);
  void HandleWorker(const std::string& identity, const proto::WorkerMessage& message);
  void SendToWorker(const std::string& identity, const proto::CoordinatorMessage& message);
  void Dispatch();
  void CheckWorkers(Clock::time_point now, bool stalled = false);
  void Quarantine(const std::string& identity, const std::string& reason);
  void FlushEvents();
  // Brings the figures the metrics do not get as they happen up to date.
  void RefreshMetrics(Clock::time_point now);
  proto::JobStatus StatusOf(const std::string& job_id);
  // StatusOf a job `requester` may see; any other is UNKNOWN_JOB, as if it did not exist.
  proto::JobStatus StatusFor(const std::string& job_id, const Requester& requester);
  void Collect();

  // Job threads.
  void JobLoop(const std::stop_token& stop);
  void RunJob(const std::string& job_id);
  void Touch(const std::string& job_id);
  void Schedule(const std::string& job_id);

  CoordinatorOptions options_;
  spdlog::level::level_enum notice_;
  // Workers' faults: warnings for a service's operator, but in an embedded run (quiet) the
  // workers are the user's own process, and a run paused with Ctrl-Z is no fault.
  spdlog::level::level_enum worker_warning_;
  WireLimits limits_;
  Waker waker_;
  std::optional<ZapHandler> zap_;  // bound before the CURVE sockets, as ZeroMQ requires
  zmq::socket_t clients_;
  zmq::socket_t workers_;

  std::mutex store_mutex_;  // guards store_ and files_
  JobStore store_;
  // The broker's own connection, for its reads: in WAL mode a read never waits for a writer, and
  // the broker never waits for a job thread that holds store_mutex_ while it waits for one (the
  // upload intake storing a large dataset). Broker thread only.
  JobStore reader_;
  TempDir files_dir_;
  DatasetFiles files_;

  std::size_t upload_chunk_bytes_;  // what a chunk holds at most: a frame's room, at most
  UploadTable uploads_;             // broker thread only
  std::mutex answers_mutex_;
  std::deque<UploadIntake::Answer> answers_;  // from the upload intake, for the broker to send
  UploadIntake intake_;                       // after what its answers go through

  TaskBoard board_;
  WorkerTable table_;                             // broker thread only
  std::atomic<std::uint32_t> worker_threads_{0};  // of the workers now known, for reports
  std::multimap<std::string, Watcher> watchers_;  // broker thread only
  Clock::time_point next_heartbeat_;
  Clock::time_point next_collection_;
  Clock::time_point next_metrics_;

  Metrics metrics_;
  std::optional<MetricsServer> metrics_server_;  // reads metrics_ alone, on threads of its own

  std::mutex jobs_mutex_;
  std::condition_variable jobs_cv_;
  std::deque<std::string> runnable_;
  std::set<std::string> touched_;  // jobs whose status changed since the last flush
  // OpenMP threads per job thread: what the process had when the coordinator started.
  const int job_omp_threads_ = std::max(1, omp_get_max_threads());
  std::vector<std::jthread> job_threads_;  // last: they stop before what they use goes
};

Coordinator::Impl::Impl(zmq::context_t& context, CoordinatorOptions options)
    : options_(std::move(options)),
      notice_(options_.quiet ? spdlog::level::debug : spdlog::level::info),
      worker_warning_(options_.quiet ? spdlog::level::debug : spdlog::level::warn),
      clients_(context, zmq::socket_type::router),
      workers_(context, zmq::socket_type::router),
      store_(options_.db),
      reader_(options_.db),
      files_dir_("evoslam-coordinator"),
      files_(files_dir_.path()),
      upload_chunk_bytes_(
          std::clamp<std::size_t>(options_.max_message_bytes / 2, 1, kUploadChunkBytes)),
      uploads_(options_.max_uploads),
      intake_(options_.db, options_.db.string() + "-uploads",
              {.chunk_bytes = upload_chunk_bytes_,
               .window = kUploadWindow,
               .quota_bytes = options_.client_quota_bytes,
               .quiet = options_.quiet},
              [this](UploadIntake::Answer answer) {
                {
                  std::lock_guard lock(answers_mutex_);
                  answers_.push_back(std::move(answer));
                }
                waker_.Wake();
              }),
      board_([this] { waker_.Wake(); }, options_.max_task_attempts) {
  // A coordinator killed with -9 left its dataset copies behind; this one clears them.
  if (const std::size_t stale = RemoveStaleTempDirs("evoslam-coordinator")) {
    spdlog::log(notice_, "removed {} left behind by coordinators that ended without cleaning up",
                Counted(stale, "temporary dataset folder"));
  }
  MarkTempDirOwner(files_dir_.path());
  limits_.max_frame_bytes = options_.max_message_bytes;
  if (!options_.curve_secret_key.empty()) {
    std::set<std::string> clients = options_.client_keys;
    clients.insert(options_.admin_keys.begin(), options_.admin_keys.end());
    zap_.emplace(context, std::map<std::string, std::set<std::string>>{
                              {"clients", std::move(clients)}, {"workers", options_.worker_keys}});
    MakeCurveServer(clients_, {options_.curve_secret_key}, "clients");
    MakeCurveServer(workers_, {options_.curve_secret_key}, "workers");
  }
  for (zmq::socket_t* s : {&clients_, &workers_}) {
    s->set(zmq::sockopt::linger, 0);
    s->set(zmq::sockopt::router_mandatory, 1);
    // Frames a little over the limit still arrive, to be answered with TOO_LARGE; far over it,
    // ZeroMQ drops the connection before the memory is spent.
    s->set(zmq::sockopt::maxmsgsize,
           static_cast<std::int64_t>(options_.max_message_bytes + (std::size_t{1} << 20)));
  }
  Bind(clients_, options_.clients_endpoint, "clients");
  Bind(workers_, options_.workers_endpoint, "workers");
  if (options_.metrics_address) {
    metrics_server_.emplace(*options_.metrics_address, [this] { return metrics_.Render(); });
  }

  if (const std::size_t dropped = store_.DropUnheldDatasets()) {
    spdlog::log(notice_, "dropped {} that a coordinator ended in the middle of storing",
                Counted(dropped, "dataset"));
  }
  Collect();
  for (const std::string& id : store_.Unfinished()) runnable_.push_back(id);
  if (!runnable_.empty()) spdlog::log(notice_, "resuming {} unfinished jobs", runnable_.size());
  for (std::size_t i = 0; i < std::max<std::size_t>(1, options_.max_running_jobs); ++i)
    job_threads_.emplace_back([this](std::stop_token stop) { JobLoop(stop); });
}

Coordinator::Impl::~Impl() {
  board_.Shutdown();
  for (auto& t : job_threads_) t.request_stop();
  jobs_cv_.notify_all();
  job_threads_.clear();
}

void Coordinator::Impl::Run(const std::stop_token& stop) {
  spdlog::log(notice_, "coordinator: clients on {}, workers on {}{}{}", clients_endpoint(),
              workers_endpoint(), metrics_server_ ? ", metrics on " + metrics_url() : "",
              zap_ ? ", CURVE on" : "");
  next_heartbeat_ = Clock::now();
  // Longer than this between two turns of the loop, the process was stopped or starved: its
  // workers gave up on it meanwhile, and what its sockets hold from them is stale.
  const Clock::duration stall =
      Seconds(options_.heartbeat_seconds * options_.liveness) + std::chrono::milliseconds(100);
  Clock::time_point turned = Clock::now();
  while (!stop.stop_requested()) {
    std::vector<zmq::pollitem_t> items = {
        {clients_.handle(), 0, ZMQ_POLLIN, 0},
        {workers_.handle(), 0, ZMQ_POLLIN, 0},
        {nullptr, waker_.fd(), ZMQ_POLLIN, 0},
    };
    if (zap_) items.push_back({zap_->socket().handle(), 0, ZMQ_POLLIN, 0});
    zmq::poll(items, std::chrono::milliseconds(100));
    if (items[2].revents & ZMQ_POLLIN) waker_.Drain();
    const Clock::time_point woke = Clock::now();
    if (woke - turned > stall) {
      spdlog::log(worker_warning_,
                  "the coordinator did not run for {:.1f} s; workers not heard from since must "
                  "introduce themselves again",
                  std::chrono::duration<double>(woke - turned).count());
      CheckWorkers(woke, true);
    }
    turned = woke;
    if (zap_ && (items[3].revents & ZMQ_POLLIN)) zap_->HandleOne();
    if (items[0].revents & ZMQ_POLLIN) OnClientFrames();
    if (items[1].revents & ZMQ_POLLIN) OnWorkerFrames();
    const Clock::time_point now = Clock::now();
    CheckWorkers(now);
    if (now >= next_heartbeat_) {
      proto::CoordinatorMessage beat;
      beat.mutable_heartbeat();
      for (const std::string& id : table_.Identities()) SendToWorker(id, beat);
      next_heartbeat_ = now + Seconds(options_.heartbeat_seconds);
    }
    SendUploadAnswers();
    DropSilentUploads(now);
    Dispatch();
    FlushEvents();
    worker_threads_ = table_.threads();
    if (options_.retention_seconds > 0 && now >= next_collection_) Collect();
    if (metrics_server_ && now >= next_metrics_) RefreshMetrics(now);
  }
  spdlog::log(notice_, "coordinator: stopping; running jobs resume at the next start");
}

// ---- Clients ----

void Coordinator::Impl::OnClientFrames() {
  // A bounded batch per wake-up, so a flood of clients cannot starve the workers.
  for (int batch = 0; batch < 256; ++batch) {
    auto frames = ReceiveFrames(clients_);
    if (!frames) return;
    if (frames->empty()) continue;
    const std::string identity = Text(frames->front());
    std::optional<proto::ClientReply> reply;
    if (frames->size() != 2) {
      spdlog::warn("client {}: refused a message of {} frames", Peer(identity), frames->size());
      reply = ErrorReplyFor(
          0, proto::ERROR_CODE_MALFORMED,
          "a request is exactly one frame, got " + std::to_string(frames->size() - 1));
    } else {
      try {
        proto::ClientRequest request = DecodeClientRequest(Bytes((*frames)[1]), limits_);
        Requester requester;
        if (zap_) {
          requester.key = UserId((*frames)[1]);
          requester.admin = options_.admin_keys.contains(requester.key);
        }
        reply = Handle(identity, requester, request);
      } catch (const ProtocolError& e) {
        spdlog::warn("client {}: refused: {}", Peer(identity), e.what());
        reply = ErrorReplyFor(0, e.code(), e.what());
      }
    }
    if (reply) SendTo(clients_, identity, Encode(std::move(*reply)));
  }
}

std::optional<proto::ClientReply> Coordinator::Impl::Handle(const std::string& identity,
                                                            const Requester& requester,
                                                            proto::ClientRequest& request) {
  proto::ClientReply reply;
  try {
    switch (request.request_case()) {
      case proto::ClientRequest::kUpload:
        Upload(identity, request, requester);
        return std::nullopt;
      case proto::ClientRequest::kChunk:
        Chunk(identity, request, requester);
        return std::nullopt;
      case proto::ClientRequest::kSubmit:
        reply = Submit(request.submit(), requester);
        break;
      case proto::ClientRequest::kStatus:
        *reply.mutable_status() = StatusFor(request.status().job_id(), requester);
        break;
      case proto::ClientRequest::kJobs: {
        // Set even when empty: a reply with nothing in its oneof is refused as malformed.
        proto::JobList& jobs = *reply.mutable_jobs();
        const auto owner = requester.admin ? std::nullopt : std::optional(requester.key);
        for (auto& s : reader_.Jobs(owner)) *jobs.add_jobs() = std::move(s);
        break;
      }
      case proto::ClientRequest::kWatch:
        reply = Watch(identity, requester, request);
        break;
      case proto::ClientRequest::kResult:
        reply = Result(request.result().job_id(), requester);
        break;
      case proto::ClientRequest::kCancel:
        reply = Cancel(request.cancel().job_id(), requester);
        break;
      case proto::ClientRequest::kWorkers: {
        proto::WorkerList& workers = *reply.mutable_workers();  // set even when empty, as above
        for (auto& w : table_.List(Clock::now(), UnixNow())) *workers.add_workers() = std::move(w);
        break;
      }
      case proto::ClientRequest::REQUEST_NOT_SET:
        throw ProtocolError(proto::ERROR_CODE_MALFORMED, "empty request");
    }
  } catch (const ProtocolError& e) {
    spdlog::warn("client {}: refused: {}", Peer(identity), e.what());
    reply = ErrorReplyFor(request.request_id(), e.code(), e.what());
  } catch (const Error& e) {
    spdlog::warn("client {}: refused: {}", Peer(identity), e.what());
    reply = ErrorReplyFor(request.request_id(), proto::ERROR_CODE_INVALID, e.what());
  } catch (const std::exception& e) {
    spdlog::error("client {}: internal error: {}", Peer(identity), e.what());
    reply = ErrorReplyFor(request.request_id(), proto::ERROR_CODE_INTERNAL, e.what());
  }
  reply.set_request_id(request.request_id());
  return reply;
}

void Coordinator::Impl::Upload(const std::string& identity, const proto::ClientRequest& request,
                               const Requester& requester) {
  const proto::UploadDataset& upload = request.upload();
  ValidateDatasetRef(Ref(upload.sha256()), "dataset");
  if (upload.has_size_bytes() && upload.size_bytes() > options_.max_dataset_bytes) {
    throw ProtocolError(proto::ERROR_CODE_TOO_LARGE,
                        "dataset " + upload.name() + " of " + std::to_string(upload.size_bytes()) +
                            " bytes is over the limit of " +
                            std::to_string(options_.max_dataset_bytes));
  }
  // The intake asks the database (the bytes may be the client's already, its quota may have no
  // room): a store under way may hold the database for a while, and the broker must not wait.
  // The client's uploads under way count against its quota as if stored.
  const std::uint64_t reserved = uploads_.Reserved(requester.key);
  std::string id = uploads_.Begin(requester.key, upload.name(), upload.size_bytes(), Clock::now());
  spdlog::debug("client {}: {} of dataset {} ({} bytes) starts", Peer(identity), id, upload.name(),
                upload.size_bytes());
  intake_.Start(identity, request.request_id(), std::move(id), upload.name(), upload.sha256(),
                upload.has_size_bytes() ? std::optional(upload.size_bytes()) : std::nullopt,
                requester.key, reserved, UnixNow());
}

void Coordinator::Impl::Chunk(const std::string& identity, proto::ClientRequest& request,
                              const Requester& requester) {
  const std::string id = request.chunk().upload_id();
  try {
    // Refused here, an oversized chunk never waits in the intake's queue.
    CheckChunkSize(request.chunk().content().size(), upload_chunk_bytes_, id);
    uploads_.Accept(id, requester.key, Clock::now());
  } catch (const ProtocolError& e) {
    if (e.code() != proto::ERROR_CODE_UNKNOWN_UPLOAD) {
      // Refused, the upload cannot go on: its next chunk would come out of order.
      uploads_.End(id);
      intake_.Drop(id);
    }
    throw;
  }
  intake_.Append(identity, request.request_id(), std::move(*request.mutable_chunk()));
}

void Coordinator::Impl::SendUploadAnswers() {
  std::deque<UploadIntake::Answer> answers;
  {
    std::lock_guard lock(answers_mutex_);
    answers.swap(answers_);
  }
  const Clock::time_point now = Clock::now();
  for (UploadIntake::Answer& answer : answers) {
    if (answer.ended) {
      uploads_.End(answer.upload_id);
    } else {
      uploads_.Answered(answer.upload_id, now);
    }
    if (answer.reply.has_error()) {
      // Asking for a dataset by hash before uploading it is routine, not a fault.
      const bool routine = answer.reply.error().code() == proto::ERROR_CODE_UNKNOWN_DATASET;
      spdlog::log(routine ? spdlog::level::debug : spdlog::level::warn, "client {}: refused: {}",
                  Peer(answer.identity), answer.reply.error().message());
    }
    if (!SendTo(clients_, answer.identity, Encode(std::move(answer.reply))) && !answer.ended) {
      // Its client's connection is closed: nobody will send the rest.
      spdlog::log(notice_, "{} of dataset {} is dropped: its client is gone", answer.upload_id,
                  uploads_.NameOf(answer.upload_id));
      uploads_.End(answer.upload_id);
      intake_.Drop(answer.upload_id);
    }
  }
}

void Coordinator::Impl::DropSilentUploads(Clock::time_point now) {
  for (const std::string& id : uploads_.Silent(now - Seconds(options_.upload_timeout_seconds))) {
    spdlog::log(notice_, "{} of dataset {} is dropped: its client sent nothing for {:g} s", id,
                uploads_.NameOf(id), options_.upload_timeout_seconds);
    uploads_.End(id);
    intake_.Drop(id);
  }
}

proto::ClientReply Coordinator::Impl::Submit(const proto::SubmitJob& submit,
                                             const Requester& requester) {
  CheckSubmitId(submit.submit_id());
  // The spec as the client sent it, which its retries send again byte for byte.
  const JobStore::Submit key{submit.submit_id(), Sha256Hex(submit.spec().SerializeAsString())};
  const std::optional<JobStore::Submitted> earlier = reader_.FindSubmit(requester.key, key.id);
  // A retry of a submit whose answer was lost: its job exists, and counts against no limit again.
  // (The broker thread alone adds jobs, so none can appear under this id meanwhile.)
  if (earlier) {
    if (earlier->spec_sha256 != key.spec_sha256) {
      throw ProtocolError(proto::ERROR_CODE_INVALID,
                          "submit id " + key.id + " already made " + earlier->job_id +
                              " with another spec; a new job needs a new submit id");
    }
    spdlog::log(notice_, "{}: submitted again (submit id {}); the same job", earlier->job_id,
                key.id);
    metrics_.CountRepeatedSubmit();
    proto::ClientReply reply;
    reply.mutable_accepted()->set_job_id(earlier->job_id);
    return reply;
  }
  proto::JobSpec spec = submit.spec();
  PrepareJobSpec(spec);
  const auto refs = JobDatasets(spec);
  // Only the broker adds jobs and drops owners (Collect): what it reads here still holds when
  // it adds the job.
  for (const auto& [what, ref] : refs) {
    ValidateDatasetRef(ref, what);
    if (!reader_.OwnsDataset(ref.sha256(), requester.key)) {
      throw ProtocolError(
          proto::ERROR_CODE_UNKNOWN_DATASET,
          std::string(what) + " " + ref.name() + " (" + ref.sha256() + ") has not been uploaded");
    }
  }
  CheckJobFileReferences(spec, [&](const proto::DatasetRef& ref) {
    return reader_.Dataset(ref.sha256()).value_or("");
  });
  if (reader_.CountUnfinished() >= options_.max_queued_jobs) {
    throw ProtocolError(proto::ERROR_CODE_QUEUE_FULL,
                        "the queue is full (" + std::to_string(options_.max_queued_jobs) +
                            " jobs queued or running); try again later");
  }
  std::string id;
  {
    std::lock_guard lock(store_mutex_);
    id = store_.AddJob(spec, requester.key, UnixNow(), key);
  }
  spdlog::log(notice_, "{}: queued", id);
  metrics_.CountSubmit();
  Schedule(id);
  proto::ClientReply reply;
  reply.mutable_accepted()->set_job_id(id);
  return reply;
}

proto::JobStatus Coordinator::Impl::StatusOf(const std::string& job_id) {
  auto status = reader_.Status(job_id);
  if (!status) throw ProtocolError(proto::ERROR_CODE_UNKNOWN_JOB, "no job " + job_id.substr(0, 64));
  return *status;
}

proto::JobStatus Coordinator::Impl::StatusFor(const std::string& job_id,
                                              const Requester& requester) {
  const auto owner = reader_.Owner(job_id);
  if (!owner || !requester.Sees(*owner)) {
    throw ProtocolError(proto::ERROR_CODE_UNKNOWN_JOB, "no job " + job_id.substr(0, 64));
  }
  return StatusOf(job_id);
}

proto::ClientReply Coordinator::Impl::Watch(const std::string& identity, const Requester& requester,
                                            const proto::ClientRequest& request) {
  const std::string& job_id = request.watch().job_id();
  proto::ClientReply reply;
  *reply.mutable_event()->mutable_status() = StatusFor(job_id, requester);
  if (!IsFinished(reply.event().status().state())) {
    if (watchers_.size() >= options_.max_watchers) {
      throw ProtocolError(proto::ERROR_CODE_QUEUE_FULL, "too many clients are watching jobs");
    }
    watchers_.emplace(job_id, Watcher{identity, request.request_id()});
  }
  return reply;
}

proto::ClientReply Coordinator::Impl::Result(const std::string& job_id,
                                             const Requester& requester) {
  const proto::JobStatus status = StatusFor(job_id, requester);
  proto::ClientReply reply;
  switch (status.state()) {
    case proto::JOB_STATE_SUCCEEDED: {
      reply.mutable_result()->set_job_id(job_id);
      for (auto& f : reader_.Result(job_id)) *reply.mutable_result()->add_files() = std::move(f);
      return reply;
    }
    case proto::JOB_STATE_FAILED:
      throw Error(job_id + " failed: " + status.error());
    case proto::JOB_STATE_CANCELLED:
      throw Error(job_id + " was cancelled");
    default:
      throw ProtocolError(proto::ERROR_CODE_NOT_FINISHED, job_id + " has not finished yet");
  }
}

proto::ClientReply Coordinator::Impl::Cancel(const std::string& job_id,
                                             const Requester& requester) {
  StatusFor(job_id, requester);  // throws for a job unknown to the requester
  bool cancelled = false;
  {
    std::lock_guard lock(store_mutex_);
    cancelled =
        store_.Finish(job_id, proto::JOB_STATE_CANCELLED, "cancelled by a client", UnixNow());
  }
  if (cancelled) {
    board_.Cancel(job_id);
    spdlog::log(notice_, "{}: cancelled", job_id);
    Touch(job_id);
  }
  proto::ClientReply reply;
  *reply.mutable_status() = StatusOf(job_id);
  return reply;
}

void Coordinator::Impl::FlushEvents() {
  std::set<std::string> touched;
  {
    std::lock_guard lock(jobs_mutex_);
    touched.swap(touched_);
  }
  for (const std::string& job_id : touched) {
    auto [first, last] = watchers_.equal_range(job_id);
    if (first == last) continue;
    proto::ClientReply reply;
    *reply.mutable_event()->mutable_status() = StatusOf(job_id);
    const bool finished = IsFinished(reply.event().status().state());
    for (auto it = first; it != last;) {
      reply.set_request_id(it->second.request_id);
      const bool delivered = SendTo(clients_, it->second.identity, Encode(reply));
      it = (finished || !delivered) ? watchers_.erase(it) : std::next(it);
    }
  }
}

void Coordinator::Impl::RefreshMetrics(Clock::time_point now) {
  // Twice a second: a scrape (every 15 s, typically) sees figures at most half a second old, and
  // the database's counts cost little.
  next_metrics_ = now + std::chrono::milliseconds(500);
  const std::size_t quarantined = table_.quarantined();
  metrics_.SetWorkers(table_.size() - quarantined, quarantined);
  metrics_.SetTasks(table_.busy(), board_.waiting());
  metrics_.SetUploadsInProgress(uploads_.size());
  const JobStore::Totals totals = reader_.CountTotals();
  metrics_.SetStored(totals.jobs, totals.stored_bytes);
}

void Coordinator::Impl::Collect() {
  // A quarter of the retention between two collections, so nothing outstays it by much, but at
  // least a second and at most ten minutes apart.
  next_collection_ = Clock::now() + Seconds(std::clamp(options_.retention_seconds / 4, 1.0, 600.0));
  if (options_.retention_seconds <= 0) return;
  JobStore::Collected collected;
  {
    std::lock_guard lock(store_mutex_);
    collected = store_.Collect(UnixNow(), options_.retention_seconds);
  }
  if (collected.jobs > 0 || collected.datasets > 0) {
    spdlog::log(notice_, "collected {} and {} past the retention of {} s",
                Counted(collected.jobs, "ended job"), Counted(collected.datasets, "unused dataset"),
                options_.retention_seconds);
  }
}

// ---- Workers ----

void Coordinator::Impl::OnWorkerFrames() {
  for (int batch = 0; batch < 256; ++batch) {
    auto frames = ReceiveFrames(workers_);
    if (!frames) return;
    if (frames->size() != 2) {
      spdlog::warn("worker {}: dropped a message of {} frames",
                   frames->empty() ? "?" : Peer(Text(frames->front())), frames->size());
      continue;
    }
    const std::string identity = Text(frames->front());
    try {
      HandleWorker(identity, DecodeWorkerMessage(Bytes((*frames)[1]), limits_));
    } catch (const ProtocolError& e) {
      spdlog::warn("worker {}: dropped: {}", Peer(identity), e.what());
    } catch (const std::exception& e) {
      spdlog::warn("worker {}: dropped a message: {}", Peer(identity), e.what());
    }
  }
}

void Coordinator::Impl::SendToWorker(const std::string& identity,
                                     const proto::CoordinatorMessage& message) {
  if (SendTo(workers_, identity, Encode(message))) return;
  // Its connection is closed: the worker ended, or reconnected on a new one.
  const auto task = table_.Remove(identity);
  if (task && message.has_task()) {
    // Never delivered: not the task's fault.
    board_.Return(*task);
    spdlog::log(notice_, "worker {} is gone (its connection is closed); {} goes to another",
                Peer(identity), *task);
    return;
  }
  if (task) board_.Requeue(*task);
  spdlog::log(notice_, "worker {} is gone (its connection is closed){}", Peer(identity),
              task ? " in the middle of task " + *task + "; it goes to another" : "");
}

void Coordinator::Impl::HandleWorker(const std::string& identity,
                                     const proto::WorkerMessage& message) {
  const Clock::time_point now = Clock::now();
  if (message.has_ready()) {
    // A repeated Ready is no restart (see WorkerTable::Ready). Taken for one, it would make the
    // worker idle while a task is on its way to it: it would be sent a second, refuse it as
    // busy, and the refusal would fail the job.
    const WorkerTable::Arrival arrival = table_.Ready(identity, message.ready(), now);
    if (arrival.is_new) {
      if (arrival.replaced_task) board_.Return(*arrival.replaced_task);
      spdlog::log(
          notice_, "worker {} ({}, {}) is ready{}{}", Peer(identity),
          message.ready().hostname().substr(0, 64), Counted(message.ready().threads(), "thread"),
          arrival.replaced ? "; it was " + Peer(*arrival.replaced) +
                                 (arrival.replaced_task ? ", whose task " + *arrival.replaced_task +
                                                              " goes to another"
                                                        : "")
                           : "",
          arrival.quarantined ? " (quarantined)" : "");
    } else {
      spdlog::debug("worker {} said Ready again", Peer(identity));
    }
    return;
  }
  if (!table_.Seen(identity, now)) {
    // A worker we dropped (silent too long) or never met: it must say Ready again, and whatever
    // it answers meanwhile is a straggler's.
    if (message.has_result()) {
      spdlog::log(worker_warning_, "dropped a late answer for {} from worker {}",
                  message.result().task_id(), Peer(identity));
    }
    proto::CoordinatorMessage bye;
    bye.mutable_disconnect()->set_reason("unknown worker: send Ready");
    SendTo(workers_, identity, Encode(bye));
    return;
  }
  switch (message.message_case()) {
    case proto::WorkerMessage::kHeartbeat:
      break;
    case proto::WorkerMessage::kFetch: {
      proto::CoordinatorMessage reply;
      proto::DatasetContent& content = *reply.mutable_dataset();
      content.mutable_dataset()->set_sha256(message.fetch().sha256().substr(0, 64));
      std::optional<std::string> bytes = reader_.Dataset(message.fetch().sha256());
      if (bytes) {
        content.mutable_dataset()->set_size_bytes(bytes->size());
        content.set_content(std::move(*bytes));
      }
      SendToWorker(identity, reply);
      break;
    }
    case proto::WorkerMessage::kResult: {
      const proto::TaskResult& result = message.result();
      if (table_.TaskOf(identity) != result.task_id()) {
        spdlog::log(worker_warning_,
                    "dropped an answer for {} from worker {}: it holds another task",
                    result.task_id(), Peer(identity));
        break;
      }
      if (result.has_error() && result.error().code() == proto::ERROR_CODE_QUEUE_FULL) {
        // Busy with work we no longer count on: the task goes to another, and the worker
        // introduces itself again once it is free.
        table_.Remove(identity);
        board_.Requeue(result.task_id());
        proto::CoordinatorMessage bye;
        bye.mutable_disconnect()->set_reason("busy with a task given to another: send Ready");
        SendTo(workers_, identity, Encode(bye));
        spdlog::log(worker_warning_, "worker {} was busy; {} goes to another", Peer(identity),
                    result.task_id());
        break;
      }
      if (result.has_error() && result.worker_fault()) {
        // The worker's fault, not the task's: the task goes to another.
        const int faults = table_.Failed(identity);
        board_.Return(result.task_id());
        spdlog::log(worker_warning_, "worker {} could not run {}: {}; it goes to another",
                    Peer(identity), result.task_id(), result.error().message().substr(0, 300));
        if (faults >= options_.quarantine_after) {
          Quarantine(identity, "failed " + Counted(faults, "task") +
                                   " in a row: " + result.error().message().substr(0, 200));
        }
        break;
      }
      if (const auto invalid = board_.Check(result)) {
        // A buggy or hostile worker: its answer is dropped, and so is the worker (its task goes
        // to another).
        Quarantine(identity, "sent an invalid result for " + result.task_id() + ": " + *invalid);
        break;
      }
      const auto held = table_.HeldFor(identity, now);
      table_.Done(identity);
      if (!board_.Complete(result)) {
        spdlog::debug("dropped the answer for {}: nobody waits for it", result.task_id());
      } else if (held) {
        metrics_.ObserveTaskLatency(std::chrono::duration<double>(*held).count());
      }
      break;
    }
    case proto::WorkerMessage::kDisconnect: {
      const auto task = table_.Remove(identity);
      if (task) board_.Requeue(*task);
      spdlog::log(notice_, "worker {} left: {}{}", Peer(identity),
                  message.disconnect().reason().substr(0, 200),
                  task ? " (its task " + *task + " goes to another)" : "");
      break;
    }
    default:
      break;
  }
}

void Coordinator::Impl::Dispatch() {
  while (table_.HasIdle()) {
    std::optional<proto::Task> task = board_.Take();
    if (!task) return;
    const Clock::time_point now = Clock::now();
    const auto identity =
        table_.Assign(task->task_id(), now, now + Seconds(options_.task_timeout_seconds));
    proto::CoordinatorMessage message;
    *message.mutable_task() = std::move(*task);
    SendToWorker(*identity, message);
  }
}

void Coordinator::Impl::CheckWorkers(Clock::time_point now, bool stalled) {
  const Clock::time_point silent_since =
      now - Seconds(options_.heartbeat_seconds * options_.liveness);
  for (const std::string& identity : table_.Lost(now, silent_since)) {
    const auto task = table_.Remove(identity);
    if (stalled) {
      // The coordinator fell silent, not the worker: the task is not to blame.
      spdlog::log(notice_, "worker {} is dropped after the stall{}", Peer(identity),
                  task ? "; its task " + *task + " goes to another" : "");
      if (task) board_.Return(*task);
    } else {
      spdlog::log(worker_warning_, "worker {} is lost (silent or overdue){}", Peer(identity),
                  task ? "; its task " + *task + " goes to another" : "");
      if (task) board_.Requeue(*task);
    }
    proto::CoordinatorMessage bye;
    bye.mutable_disconnect()->set_reason("silent or overdue: send Ready");
    SendTo(workers_, identity, Encode(bye));
  }
  for (const std::string& identity : table_.Release(now)) {
    spdlog::log(notice_, "worker {} is back in the pool after its quarantine", Peer(identity));
  }
}

void Coordinator::Impl::Quarantine(const std::string& identity, const std::string& reason) {
  const auto task =
      table_.Quarantine(identity, Clock::now() + Seconds(options_.quarantine_seconds), reason);
  if (task) board_.Return(*task);
  spdlog::log(worker_warning_, "worker {} is dropped from the pool for {:g} s (quarantined): {}",
              Peer(identity), options_.quarantine_seconds, reason);
}

// ---- Jobs ----

void Coordinator::Impl::Schedule(const std::string& job_id) {
  {
    std::lock_guard lock(jobs_mutex_);
    runnable_.push_back(job_id);
  }
  jobs_cv_.notify_one();
}

void Coordinator::Impl::Touch(const std::string& job_id) {
  {
    std::lock_guard lock(jobs_mutex_);
    touched_.insert(job_id);
  }
  waker_.Wake();
}

void Coordinator::Impl::JobLoop(const std::stop_token& stop) {
  // A job's own heavy steps (a SLAM loop check's coarse match) run while its workers wait, so
  // they may use the host's cores; the small ones stay on one thread by their own thresholds.
  omp_set_num_threads(job_omp_threads_);
  for (;;) {
    std::string job_id;
    {
      std::unique_lock lock(jobs_mutex_);
      jobs_cv_.wait(lock, [&] { return stop.stop_requested() || !runnable_.empty(); });
      if (stop.stop_requested()) return;
      job_id = std::move(runnable_.front());
      runnable_.pop_front();
    }
    RunJob(job_id);
  }
}

void Coordinator::Impl::RunJob(const std::string& job_id) {
  JobContext context;
  context.job_id = job_id;
  context.board = &board_;
  context.files = &files_;
  context.checkpoint_seconds = options_.checkpoint_seconds;
  context.worker_threads = worker_threads_;
  std::uint64_t slot_epoch = 0;
  try {
    {
      std::lock_guard lock(store_mutex_);
      const auto status = store_.Status(job_id);
      if (!status || IsFinished(status->state())) return;  // cancelled while it waited
      context.spec = *store_.Spec(job_id);
      for (const auto& [what, ref] : JobDatasets(context.spec)) {
        if (files_.Find(ref)) continue;
        const auto content = store_.Dataset(ref.sha256());
        if (!content)
          throw Error(std::string(what) + " " + ref.name() + " is missing from the database");
        files_.Put(ref, *content);
      }
      const auto checkpoints = store_.Checkpoints(job_id);
      if (!checkpoints.empty()) {
        context.resume = checkpoints.front().bytes;
        slot_epoch = checkpoints.front().epoch;
      }
      proto::JobStatus starting;
      starting.set_phase(context.resume ? "resuming" : "loading");
      store_.SetRunning(job_id, starting);
    }
    spdlog::log(notice_, "{}: {}", job_id,
                context.resume ? "resuming from its checkpoint" : "running");
    Touch(job_id);
    context.save_checkpoint = [&](const std::string& bytes) {
      std::lock_guard lock(store_mutex_);
      store_.SaveCheckpoint(job_id, 0, ++slot_epoch, bytes);
    };
    ProgressThrottle throttle(std::chrono::milliseconds(200));
    context.progress = [&](const proto::JobStatus& p) {
      if (!throttle.Admit(p, ProgressThrottle::Clock::now())) return;
      {
        std::lock_guard lock(store_mutex_);
        store_.SetRunning(job_id, p);
      }
      Touch(job_id);
    };
    const std::vector<proto::ResultFile> files = RunJobOfKind(context);
    bool succeeded = false;
    {
      std::lock_guard lock(store_mutex_);
      succeeded = store_.Succeed(job_id, files, UnixNow());
    }
    if (succeeded) spdlog::log(notice_, "{}: succeeded", job_id);
  } catch (const JobInterrupted& e) {
    spdlog::log(notice_, "{}: {}", job_id, e.what());
  } catch (const std::exception& e) {
    // Quiet (embedded), the client that waits for the job reports its failure, once.
    spdlog::log(options_.quiet ? spdlog::level::debug : spdlog::level::warn, "{}: failed: {}",
                job_id, e.what());
    std::lock_guard lock(store_mutex_);
    store_.Finish(job_id, proto::JOB_STATE_FAILED, e.what(), UnixNow());
  }
  Touch(job_id);
}

// ---- Coordinator ----

Coordinator::Coordinator(zmq::context_t& context, CoordinatorOptions options)
    : impl_(std::make_unique<Impl>(context, std::move(options))) {}
Coordinator::~Coordinator() = default;
void Coordinator::Run(std::stop_token stop) { impl_->Run(stop); }
std::string Coordinator::clients_endpoint() const { return impl_->clients_endpoint(); }
std::string Coordinator::workers_endpoint() const { return impl_->workers_endpoint(); }
std::string Coordinator::metrics_url() const { return impl_->metrics_url(); }

}  // namespace evoslam
