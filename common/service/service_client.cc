#include "common/service/service_client.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <fstream>
#include <sstream>
#include <system_error>
#include <utility>

#include "common/service/job_state.h"
#include "common/util/error.h"
#include "common/util/random_id.h"
#include "common/util/sha256.h"

namespace evoslam {
namespace {

using Clock = std::chrono::steady_clock;

// "30 s", "0.5 s": a timeout as the user gave it.
std::string Seconds(double s) { return fmt::format("{:g} s", s); }

std::string Trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\"'");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\"'");
  return s.substr(first, last - first + 1);
}

}  // namespace

std::optional<std::string> MapYamlImage(const std::string& yaml) {
  std::istringstream in(yaml);
  std::string line;
  while (std::getline(in, line)) {
    const std::string t = Trim(line);
    if (t.rfind("image:", 0) == 0) return Trim(t.substr(6));
  }
  return std::nullopt;
}

std::string WithMapYamlImage(const std::string& yaml, const std::string& image) {
  std::istringstream in(yaml);
  std::string line, out;
  while (std::getline(in, line)) {
    out += Trim(line).rfind("image:", 0) == 0 ? "image: " + image : line;
    out += '\n';
  }
  return out;
}

ServiceClient::ServiceClient(zmq::context_t& context, ClientOptions options)
    : options_(std::move(options)), socket_(context, zmq::socket_type::dealer) {
  socket_.set(zmq::sockopt::linger, 0);
  // A send with no connection up would otherwise block for ever.
  socket_.set(zmq::sockopt::sndtimeo,
              static_cast<int>(std::min(1e9, 1000.0 * options_.timeout_seconds)));
  if (options_.curve) MakeCurveClient(socket_, *options_.curve);
  Connect(socket_, options_.endpoint, "the coordinator");
}

std::uint64_t ServiceClient::Send(proto::ClientRequest request) {
  const std::uint64_t id = next_request_++;
  request.set_request_id(id);
  if (!evoslam::Send(socket_, Encode(std::move(request)))) {
    throw Error("cannot reach the coordinator at " + options_.endpoint + " within " +
                Seconds(options_.timeout_seconds));
  }
  return id;
}

std::optional<proto::ClientReply> ServiceClient::Receive(
    const std::vector<std::uint64_t>& request_ids, double timeout_seconds) {
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(timeout_seconds));
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    std::vector<zmq::pollitem_t> items = {{socket_.handle(), 0, ZMQ_POLLIN, 0}};
    zmq::poll(items, left);
    while (auto frames = ReceiveFrames(socket_)) {
      if (frames->size() != 1) continue;
      proto::ClientReply reply = DecodeClientReply(Bytes(frames->front()));
      // Replies to requests given up on, and requests refused before they could be read
      // (id 0), are told apart by their ids.
      if (std::ranges::find(request_ids, reply.request_id()) != request_ids.end()) return reply;
      if (reply.request_id() == 0 && reply.has_error()) {
        throw ProtocolError(reply.error().code(), "coordinator: " + reply.error().message());
      }
    }
  }
}

proto::ClientReply ServiceClient::Call(proto::ClientRequest request, int attempts) {
  attempts = std::max(1, attempts);
  std::vector<std::uint64_t> sent;
  std::optional<proto::ClientReply> reply;
  while (!reply && static_cast<int>(sent.size()) < attempts) {
    // The last send may have the request: its bytes are not copied for nothing.
    const bool last = static_cast<int>(sent.size()) + 1 == attempts;
    sent.push_back(last ? Send(std::move(request)) : Send(request));
    reply = Receive(sent, options_.timeout_seconds);
  }
  return Answer(std::move(reply), attempts);
}

proto::ClientReply ServiceClient::Await(std::uint64_t request_id) {
  return Answer(Receive({request_id}, options_.timeout_seconds), 1);
}

proto::ClientReply ServiceClient::Answer(std::optional<proto::ClientReply> reply,
                                         int attempts) const {
  if (!reply) {
    throw Error("no answer from the coordinator at " + options_.endpoint + " within " +
                Seconds(options_.timeout_seconds) +
                (attempts > 1 ? ", " + std::to_string(attempts) + " times" : "") +
                " (is it running? with CURVE on, are its key and this client's key right?)");
  }
  if (reply->has_error()) {
    throw ProtocolError(reply->error().code(), "coordinator: " + reply->error().message());
  }
  return std::move(*reply);
}

proto::DatasetRef ServiceClient::UploadFrom(const std::string& name, const std::string& sha256,
                                            std::uint64_t size, const ReadBytes& read) {
  proto::DatasetRef ref;
  ref.set_sha256(sha256);
  ref.set_size_bytes(size);
  ref.set_name(name);
  // One question starts the upload, or finds that the bytes need not travel: a dataset is sent
  // once, however many jobs use it.
  proto::ClientRequest start;
  start.mutable_upload()->set_name(name);
  start.mutable_upload()->set_sha256(sha256);
  start.mutable_upload()->set_size_bytes(size);
  const proto::ClientReply started = Call(std::move(start));
  if (started.has_stored()) return ref;
  if (!started.has_upload_started() || started.upload_started().chunk_bytes() == 0) {
    throw Error("the coordinator at " + options_.endpoint + " answered the upload of " + name +
                " with neither an upload nor the dataset");
  }
  const std::string& id = started.upload_started().upload_id();
  const std::uint64_t chunk_bytes = started.upload_started().chunk_bytes();
  const std::size_t window = std::max<std::uint32_t>(1, started.upload_started().window());
  // Up to `window` chunks travel ahead of their answers, so the next one is on its way while the
  // coordinator writes the last. Answers come in order.
  std::deque<std::uint64_t> waiting;
  std::uint64_t offset = 0;
  bool sent_last = false;
  for (;;) {
    while (!sent_last && waiting.size() < window) {
      proto::ClientRequest request;
      proto::UploadChunk& chunk = *request.mutable_chunk();
      chunk.set_upload_id(id);
      chunk.set_offset(offset);
      std::string& bytes = *chunk.mutable_content();
      bytes.resize(static_cast<std::size_t>(std::min(chunk_bytes, size - offset)));
      read(bytes);
      offset += bytes.size();
      sent_last = offset == size;
      waiting.push_back(Send(std::move(request)));
    }
    const proto::ClientReply answer = Await(waiting.front());
    waiting.pop_front();
    if (answer.has_stored()) return ref;
    if (!answer.has_chunk_stored() || (sent_last && waiting.empty())) {
      throw Error("the coordinator at " + options_.endpoint + " answered a chunk of " + name +
                  " with neither its receipt nor the dataset");
    }
  }
}

proto::DatasetRef ServiceClient::UploadBytes(const std::string& name, const std::string& content) {
  std::size_t at = 0;
  return UploadFrom(name, Sha256Hex(content), content.size(), [&](std::span<char> piece) {
    std::copy_n(content.data() + at, piece.size(), piece.data());
    at += piece.size();
  });
}

proto::DatasetRef ServiceClient::Upload(const std::filesystem::path& file) {
  // Hashed, then sent, a chunk at a time: a large log need not fit in memory.
  const std::string sha = Sha256HexOfFile(file);
  std::ifstream in(file, std::ios::binary);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error) throw InputError(file.string(), 0, "cannot read its size: " + error.message());
  if (!in) throw InputError(file.string(), 0, "cannot open it");
  return UploadFrom(file.string(), sha, size, [&](std::span<char> piece) {
    if (!in.read(piece.data(), static_cast<std::streamsize>(piece.size()))) {
      throw InputError(file.string(), 0, "cannot read it: it changed while it was uploaded");
    }
  });
}

std::string NewSubmitId() { return RandomHexId(16); }

std::string ServiceClient::Submit(const proto::JobSpec& spec) {
  return Submit(spec, NewSubmitId());
}

std::string ServiceClient::Submit(const proto::JobSpec& spec, const std::string& submit_id) {
  proto::ClientRequest r;
  *r.mutable_submit()->mutable_spec() = spec;
  r.mutable_submit()->set_submit_id(submit_id);
  // A submit that timed out may still have made its job; sent again under the same id, it is
  // answered with that job.
  return Call(std::move(r), options_.submit_attempts).accepted().job_id();
}

proto::JobStatus ServiceClient::Status(const std::string& job_id) {
  proto::ClientRequest r;
  r.mutable_status()->set_job_id(job_id);
  return Call(std::move(r)).status();
}

std::vector<proto::JobStatus> ServiceClient::Jobs() {
  proto::ClientRequest r;
  r.mutable_jobs();
  const auto reply = Call(std::move(r));
  return {reply.jobs().jobs().begin(), reply.jobs().jobs().end()};
}

proto::JobStatus ServiceClient::Watch(
    const std::string& job_id, const std::function<void(const proto::ProgressEvent&)>& on_event) {
  for (;;) {
    proto::ClientRequest r;
    r.mutable_watch()->set_job_id(job_id);
    const std::uint64_t id = Send(r);
    auto reply = Receive({id}, options_.timeout_seconds);
    if (!reply) {
      throw Error("no answer from the coordinator at " + options_.endpoint + " within " +
                  Seconds(options_.timeout_seconds));
    }
    // Events keep coming under the watch's id; a silence means a long step, or a coordinator
    // that restarted and forgot its watchers: the watch is then asked for again.
    while (reply) {
      if (reply->has_error()) {
        throw ProtocolError(reply->error().code(), "coordinator: " + reply->error().message());
      }
      if (on_event) on_event(reply->event());
      if (IsFinished(reply->event().status().state())) return reply->event().status();
      reply = Receive({id}, options_.timeout_seconds);
    }
  }
}

std::vector<proto::ResultFile> ServiceClient::Result(const std::string& job_id) {
  proto::ClientRequest r;
  r.mutable_result()->set_job_id(job_id);
  const auto reply = Call(std::move(r));
  return {reply.result().files().begin(), reply.result().files().end()};
}

proto::JobStatus ServiceClient::Cancel(const std::string& job_id) {
  proto::ClientRequest r;
  r.mutable_cancel()->set_job_id(job_id);
  return Call(std::move(r)).status();
}

std::vector<proto::WorkerInfo> ServiceClient::Workers() {
  proto::ClientRequest r;
  r.mutable_workers();
  const auto reply = Call(std::move(r));
  return {reply.workers().workers().begin(), reply.workers().workers().end()};
}

}  // namespace evoslam
