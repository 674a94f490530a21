#ifndef EVOSLAM_COMMON_PROTOCOL_WIRE_H_
#define EVOSLAM_COMMON_PROTOCOL_WIRE_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "common/util/error.h"
#include "evoslam/service.pb.h"

namespace evoslam {

// The version of proto/evoslam/service.proto this build speaks; every envelope carries it.
// 3: datasets travel in chunks (UploadDataset starts an upload, UploadChunks carry its bytes).
inline constexpr std::uint32_t kProtocolVersion = 3;

// A frame refused at the door, with the code the reply carries.
class ProtocolError : public Error {
 public:
  ProtocolError(proto::ErrorCode code, const std::string& message) : Error(message), code_(code) {}
  proto::ErrorCode code() const { return code_; }

 private:
  proto::ErrorCode code_;
};

struct WireLimits {
  // A job's results, or a dataset sent to a worker, travel whole in one frame.
  std::size_t max_frame_bytes = std::size_t{256} << 20;
};

// Decode one frame into its envelope. Throws ProtocolError when the frame is larger than the
// limit, is not a parseable envelope, speaks another protocol version, or carries no message.
// These are the entry points for bytes from the network: they never crash and never trust.
proto::ClientRequest DecodeClientRequest(std::span<const std::byte> frame,
                                         const WireLimits& limits = {});
proto::ClientReply DecodeClientReply(std::span<const std::byte> frame,
                                     const WireLimits& limits = {});
proto::WorkerMessage DecodeWorkerMessage(std::span<const std::byte> frame,
                                         const WireLimits& limits = {});
proto::CoordinatorMessage DecodeCoordinatorMessage(std::span<const std::byte> frame,
                                                   const WireLimits& limits = {});

// Serialise an envelope, stamping it with kProtocolVersion.
std::string Encode(proto::ClientRequest message);
std::string Encode(proto::ClientReply message);
std::string Encode(proto::WorkerMessage message);
std::string Encode(proto::CoordinatorMessage message);

// A reply saying why a request was refused.
proto::ClientReply ErrorReplyFor(std::uint64_t request_id, proto::ErrorCode code,
                                 const std::string& message);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_PROTOCOL_WIRE_H_
