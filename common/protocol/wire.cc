#include "common/protocol/wire.h"

#include <limits>
#include <utility>

namespace evoslam {
namespace {

// Parses, then checks what every envelope must have: our version and a message in its oneof.
template <typename Envelope, typename HasMessage>
Envelope Decode(std::span<const std::byte> frame, const WireLimits& limits, const char* what,
                HasMessage has_message) {
  if (frame.size() > limits.max_frame_bytes) {
    throw ProtocolError(proto::ERROR_CODE_TOO_LARGE, std::string(what) + " of " +
                                                         std::to_string(frame.size()) +
                                                         " bytes is over the limit of " +
                                                         std::to_string(limits.max_frame_bytes));
  }
  if (frame.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw ProtocolError(proto::ERROR_CODE_TOO_LARGE, std::string(what) + " is over 2 GiB");
  }
  Envelope envelope;
  if (!envelope.ParseFromArray(frame.data(), static_cast<int>(frame.size()))) {
    throw ProtocolError(proto::ERROR_CODE_MALFORMED, std::string(what) + " of " +
                                                         std::to_string(frame.size()) +
                                                         " bytes is not a valid protocol buffer");
  }
  if (envelope.protocol_version() != kProtocolVersion) {
    throw ProtocolError(proto::ERROR_CODE_BAD_VERSION,
                        std::string(what) + " speaks protocol version " +
                            std::to_string(envelope.protocol_version()) + ", this build speaks " +
                            std::to_string(kProtocolVersion));
  }
  if (!has_message(envelope)) {
    throw ProtocolError(proto::ERROR_CODE_MALFORMED,
                        std::string(what) + " carries no message, or one this build does not know");
  }
  return envelope;
}

template <typename Envelope>
std::string Stamped(Envelope message) {
  message.set_protocol_version(kProtocolVersion);
  return message.SerializeAsString();
}

}  // namespace

proto::ClientRequest DecodeClientRequest(std::span<const std::byte> frame,
                                         const WireLimits& limits) {
  return Decode<proto::ClientRequest>(frame, limits, "client request", [](const auto& m) {
    return m.request_case() != proto::ClientRequest::REQUEST_NOT_SET;
  });
}

proto::ClientReply DecodeClientReply(std::span<const std::byte> frame, const WireLimits& limits) {
  return Decode<proto::ClientReply>(frame, limits, "coordinator reply", [](const auto& m) {
    return m.reply_case() != proto::ClientReply::REPLY_NOT_SET;
  });
}

proto::WorkerMessage DecodeWorkerMessage(std::span<const std::byte> frame,
                                         const WireLimits& limits) {
  return Decode<proto::WorkerMessage>(frame, limits, "worker message", [](const auto& m) {
    return m.message_case() != proto::WorkerMessage::MESSAGE_NOT_SET;
  });
}

proto::CoordinatorMessage DecodeCoordinatorMessage(std::span<const std::byte> frame,
                                                   const WireLimits& limits) {
  return Decode<proto::CoordinatorMessage>(frame, limits, "coordinator message", [](const auto& m) {
    return m.message_case() != proto::CoordinatorMessage::MESSAGE_NOT_SET;
  });
}

std::string Encode(proto::ClientRequest message) { return Stamped(std::move(message)); }
std::string Encode(proto::ClientReply message) { return Stamped(std::move(message)); }
std::string Encode(proto::WorkerMessage message) { return Stamped(std::move(message)); }
std::string Encode(proto::CoordinatorMessage message) { return Stamped(std::move(message)); }

proto::ClientReply ErrorReplyFor(std::uint64_t request_id, proto::ErrorCode code,
                                 const std::string& message) {
  proto::ClientReply reply;
  reply.set_protocol_version(kProtocolVersion);
  reply.set_request_id(request_id);
  reply.mutable_error()->set_code(code);
  reply.mutable_error()->set_message(message);
  return reply;
}

}  // namespace evoslam
