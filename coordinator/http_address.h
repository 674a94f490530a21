#ifndef EVOSLAM_COORDINATOR_HTTP_ADDRESS_H_
#define EVOSLAM_COORDINATOR_HTTP_ADDRESS_H_

#include <cstdint>
#include <string>
#include <string_view>

namespace evoslam {

// Where an HTTP server listens: HOST:PORT as a user writes it.
struct HttpAddress {
  std::string host;  // an IPv4 address, a host name, or an IPv6 address (without its brackets)
  std::uint16_t port = 0;  // 0: a free port the system picks

  // HOST:PORT again, an IPv6 host in brackets: "127.0.0.1:9464", "[::1]:9464".
  std::string ToString() const;
  // Whether only this host reaches it: a loopback address (127.0.0.0/8, ::1) or localhost.
  bool IsLoopback() const;
};

// Reads HOST:PORT ("127.0.0.1:9464", "localhost:9464", "[::1]:9464", "0.0.0.0:9464"); PORT is
// 0 to 65535. Throws Error saying what is wrong and what a right one looks like.
HttpAddress ParseHttpAddress(std::string_view text);

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_HTTP_ADDRESS_H_
