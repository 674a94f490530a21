#ifndef EVOSLAM_COMMON_PROTOCOL_ZMQ_IO_H_
#define EVOSLAM_COMMON_PROTOCOL_ZMQ_IO_H_

#include <zmq.hpp>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace evoslam {

// One multipart message as it came off a socket.
using Frames = std::vector<zmq::message_t>;

// Receives one whole multipart message without blocking; nullopt when none is waiting.
std::optional<Frames> ReceiveFrames(zmq::socket_t& socket);

std::span<const std::byte> Bytes(const zmq::message_t& frame);
std::string Text(const zmq::message_t& frame);

// Sends [identity, payload] on a ROUTER socket; returns false when the peer is gone.
bool SendTo(zmq::socket_t& router, std::string_view identity, std::string_view payload);
// Sends one frame on a DEALER socket; false when it could not be queued within the socket's
// send timeout (ZMQ_SNDTIMEO), as when no connection to the peer is up.
bool Send(zmq::socket_t& dealer, std::string_view payload);

// Binds or connects a socket; an endpoint ZeroMQ refuses (a malformed address, an unknown
// transport, an address in use) throws Error naming it and what it was for: "cannot listen for
// <what> on <endpoint>: <reason>" or "cannot connect to <what> at <endpoint>: <reason>".
void Bind(zmq::socket_t& socket, const std::string& endpoint, std::string_view what);
void Connect(zmq::socket_t& socket, const std::string& endpoint, std::string_view what);

// Whether only this host can reach a socket bound to `endpoint`: tcp on a loopback address
// (127.0.0.0/8, ::1, localhost), ipc or inproc. A wildcard, any other address and any other
// host or interface name are not.
bool IsLoopbackEndpoint(std::string_view endpoint);

// The CURVE settings of a socket: a server with its secret key, or a client that knows the
// server's public key and has a key pair of its own. Keys are Z85 text.
struct CurveServerKeys {
  std::string secret_key;
};
struct CurveClientKeys {
  std::string server_public_key;
  std::string public_key;
  std::string secret_key;
};
void MakeCurveServer(zmq::socket_t& socket, const CurveServerKeys& keys, std::string_view domain);
void MakeCurveClient(zmq::socket_t& socket, const CurveClientKeys& keys);

// Loads the client side of CURVE from files: the server's .pub and this peer's .key (its public
// key is derived). Throws Error naming the file on a bad key.
CurveClientKeys LoadCurveClientKeys(const std::string& server_public_file,
                                    const std::string& secret_file);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_PROTOCOL_ZMQ_IO_H_
