#ifndef EVOSLAM_COMMON_SERVICE_SERVICE_CLIENT_H_
#define EVOSLAM_COMMON_SERVICE_SERVICE_CLIENT_H_

#include <zmq.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/protocol/wire.h"
#include "common/protocol/zmq_io.h"
#include "evoslam/service.pb.h"

namespace evoslam {

struct ClientOptions {
  std::string endpoint = "tcp://127.0.0.1:5555";
  std::optional<CurveClientKeys> curve;
  double timeout_seconds = 30.0;  // for one reply
  // Times a submit is sent in all while none of its sends is answered within the timeout. Every
  // send carries the submit's one id, so a submit that made its job before its answer was lost
  // is answered with that job, not another.
  int submit_attempts = 3;
};

// A new submit id: 32 random hex digits, drawn from the system's CSPRNG.
std::string NewSubmitId();

// A client of the coordinator's socket API (a DEALER socket). Every call waits for its reply;
// an error reply is thrown as ProtocolError with the coordinator's code and message, and no
// reply within the timeout as Error saying what was waited for.
class ServiceClient {
 public:
  ServiceClient(zmq::context_t& context, ClientOptions options);

  // Uploads a file unless the coordinator already has its bytes, and returns its reference. The
  // reference is named by the path as given, so that errors found in the file say which file. The
  // bytes go in the chunks the coordinator asks for, read from the file one at a time.
  proto::DatasetRef Upload(const std::filesystem::path& file);
  proto::DatasetRef UploadBytes(const std::string& name, const std::string& content);
  // Fills the span with the dataset's next bytes.
  using ReadBytes = std::function<void(std::span<char>)>;
  // Uploads `size` bytes hashing to `sha256`, read through `read` a chunk at a time, unless the
  // coordinator already has them.
  proto::DatasetRef UploadFrom(const std::string& name, const std::string& sha256,
                               std::uint64_t size, const ReadBytes& read);
  // Submits under a new submit id and returns the job's id.
  std::string Submit(const proto::JobSpec& spec);
  // Submits under `submit_id`: again with the same spec, the same job (as long as the coordinator
  // keeps it); with another spec, refused INVALID.
  std::string Submit(const proto::JobSpec& spec, const std::string& submit_id);
  proto::JobStatus Status(const std::string& job_id);
  std::vector<proto::JobStatus> Jobs();
  // Follows a job until it ends, calling `on_event` for every progress event; returns its final
  // status. Survives a coordinator restart: when events stop it asks again.
  proto::JobStatus Watch(const std::string& job_id,
                         const std::function<void(const proto::ProgressEvent&)>& on_event);
  std::vector<proto::ResultFile> Result(const std::string& job_id);
  proto::JobStatus Cancel(const std::string& job_id);
  std::vector<proto::WorkerInfo> Workers();

  // One request and its reply (or the first reply, for a watch). Unanswered within the timeout,
  // the request is sent again, up to `attempts` times in all, and a reply to any of the sends
  // is its reply: only for a request that means the same however often it arrives.
  proto::ClientReply Call(proto::ClientRequest request, int attempts = 1);

 private:
  std::uint64_t Send(proto::ClientRequest request);
  // The reply to `request_id`; an error reply, or none in time, throws as Call does.
  proto::ClientReply Await(std::uint64_t request_id);
  // `reply`, unless it is an error or none came to any of `attempts` sends: then throws.
  proto::ClientReply Answer(std::optional<proto::ClientReply> reply, int attempts) const;
  // The next reply to one of `request_ids`, waiting at most `timeout_seconds`; nullopt on
  // timeout.
  std::optional<proto::ClientReply> Receive(const std::vector<std::uint64_t>& request_ids,
                                            double timeout_seconds);

  ClientOptions options_;
  zmq::socket_t socket_;
  std::uint64_t next_request_ = 1;
};

// The map_server YAML's image path, as written in the file; nullopt when there is none.
std::optional<std::string> MapYamlImage(const std::string& yaml);
// The YAML with its image path replaced by `image`.
std::string WithMapYamlImage(const std::string& yaml, const std::string& image);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SERVICE_SERVICE_CLIENT_H_
