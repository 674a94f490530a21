#ifndef EVOSLAM_COORDINATOR_ZAP_HANDLER_H_
#define EVOSLAM_COORDINATOR_ZAP_HANDLER_H_

#include <zmq.hpp>

#include <map>
#include <set>
#include <string>

namespace evoslam {

// ZeroMQ's authentication hook (ZAP, RFC 27) for CURVE: a CURVE handshake on a socket whose ZAP
// domain is listed here succeeds only when the peer's public key is among that domain's keys.
// Everyone else is refused during the handshake and never gets a message through. An accepted
// peer's messages carry its public key as their User-Id.
class ZapHandler {
 public:
  // `accepted`: domain -> Z85 public keys. Binds inproc://zeromq.zap.01 in `context`, which must
  // happen before the CURVE sockets bind.
  ZapHandler(zmq::context_t& context, std::map<std::string, std::set<std::string>> accepted);

  zmq::socket_t& socket() { return socket_; }
  // Answers one waiting request, if any.
  void HandleOne();

 private:
  zmq::socket_t socket_;
  std::map<std::string, std::set<std::string>> accepted_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_ZAP_HANDLER_H_
