#include "common/protocol/zmq_io.h"

#include <arpa/inet.h>

#include <array>

#include "common/protocol/curve_keys.h"
#include "common/util/error.h"

namespace evoslam {

std::optional<Frames> ReceiveFrames(zmq::socket_t& socket) {
  Frames frames;
  zmq::message_t frame;
  if (!socket.recv(frame, zmq::recv_flags::dontwait)) return std::nullopt;
  frames.push_back(std::move(frame));
  while (frames.back().more()) {
    zmq::message_t next;
    // The rest of a multipart message is delivered with its first part.
    if (!socket.recv(next, zmq::recv_flags::none)) break;
    frames.push_back(std::move(next));
  }
  return frames;
}

std::span<const std::byte> Bytes(const zmq::message_t& frame) {
  return {static_cast<const std::byte*>(frame.data()), frame.size()};
}

std::string Text(const zmq::message_t& frame) {
  return std::string(static_cast<const char*>(frame.data()), frame.size());
}

bool SendTo(zmq::socket_t& router, std::string_view identity, std::string_view payload) {
  try {
    if (!router.send(zmq::buffer(identity), zmq::send_flags::sndmore | zmq::send_flags::dontwait))
      return false;
    return router.send(zmq::buffer(payload), zmq::send_flags::dontwait).has_value();
  } catch (const zmq::error_t&) {
    return false;  // EHOSTUNREACH with ROUTER_MANDATORY: the peer has gone
  }
}

bool Send(zmq::socket_t& dealer, std::string_view payload) {
  return dealer.send(zmq::buffer(payload), zmq::send_flags::none).has_value();
}

void Bind(zmq::socket_t& socket, const std::string& endpoint, std::string_view what) {
  try {
    socket.bind(endpoint);
  } catch (const zmq::error_t& e) {
    throw Error("cannot listen for " + std::string(what) + " on " + endpoint + ": " + e.what());
  }
}

void Connect(zmq::socket_t& socket, const std::string& endpoint, std::string_view what) {
  try {
    socket.connect(endpoint);
  } catch (const zmq::error_t& e) {
    throw Error("cannot connect to " + std::string(what) + " at " + endpoint + ": " + e.what());
  }
}

bool IsLoopbackEndpoint(std::string_view endpoint) {
  if (endpoint.starts_with("ipc://") || endpoint.starts_with("inproc://")) return true;
  if (!endpoint.starts_with("tcp://")) return false;
  std::string_view host = endpoint.substr(6);
  const std::size_t colon = host.rfind(':');
  if (colon == std::string_view::npos) return false;
  host = host.substr(0, colon);
  if (host == "localhost") return true;
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  const std::string text(host);
  std::array<unsigned char, 16> address{};
  if (::inet_pton(AF_INET, text.c_str(), address.data()) == 1) return address[0] == 127;
  return ::inet_pton(AF_INET6, text.c_str(), address.data()) == 1 &&
         address == std::array<unsigned char, 16>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
}

void MakeCurveServer(zmq::socket_t& socket, const CurveServerKeys& keys, std::string_view domain) {
  socket.set(zmq::sockopt::curve_server, 1);
  socket.set(zmq::sockopt::curve_secretkey, keys.secret_key);
  socket.set(zmq::sockopt::zap_domain, std::string(domain));
}

void MakeCurveClient(zmq::socket_t& socket, const CurveClientKeys& keys) {
  socket.set(zmq::sockopt::curve_serverkey, keys.server_public_key);
  socket.set(zmq::sockopt::curve_publickey, keys.public_key);
  socket.set(zmq::sockopt::curve_secretkey, keys.secret_key);
}

CurveClientKeys LoadCurveClientKeys(const std::string& server_public_file,
                                    const std::string& secret_file) {
  CurveClientKeys keys;
  keys.server_public_key = ReadCurveKey(server_public_file);
  keys.secret_key = ReadCurveKey(secret_file);
  keys.public_key = CurvePublicKey(keys.secret_key);
  return keys;
}

}  // namespace evoslam
