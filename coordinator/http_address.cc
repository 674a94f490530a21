#include "coordinator/http_address.h"

#include <algorithm>
#include <cctype>

#include "common/protocol/zmq_io.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

bool AllDigits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
}

bool IsHostChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' || c == '_';
}

}  // namespace

std::string HttpAddress::ToString() const {
  const bool ipv6 = host.find(':') != std::string::npos;
  return (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

// The same rule as the coordinator's ZeroMQ endpoints, so one address is local for both.
bool HttpAddress::IsLoopback() const { return IsLoopbackEndpoint("tcp://" + ToString()); }

HttpAddress ParseHttpAddress(std::string_view text) {
  const std::string given(text);
  const auto fail = [&](const std::string& why) {
    throw Error("'" + given + "' is not HOST:PORT (" + why + "), e.g. 127.0.0.1:9464");
  };
  if (text.find("://") != std::string_view::npos) fail("give it without a scheme");
  HttpAddress address;
  std::string_view port;
  if (text.starts_with('[')) {
    const std::size_t close = text.find(']');
    if (close == std::string_view::npos || close + 1 >= text.size() || text[close + 1] != ':') {
      fail("an IPv6 address in brackets, then a colon and the port");
    }
    address.host = std::string(text.substr(1, close - 1));
    port = text.substr(close + 2);
    const bool hex_or_colon = std::all_of(address.host.begin(), address.host.end(), [](char c) {
      return std::isxdigit(static_cast<unsigned char>(c)) != 0 || c == ':' || c == '.';
    });
    if (address.host.empty() || !hex_or_colon) fail("the brackets hold an IPv6 address");
  } else {
    const std::size_t colon = text.rfind(':');
    const std::string_view host = colon == std::string_view::npos ? "" : text.substr(0, colon);
    if (host.empty() && (colon != std::string_view::npos || AllDigits(text))) {
      fail("no host: 127.0.0.1 serves this host alone, 0.0.0.0 every interface");
    }
    if (colon == std::string_view::npos) fail("no port");
    address.host = std::string(host);
    port = text.substr(colon + 1);
    if (address.host.find(':') != std::string::npos) fail("an IPv6 address goes in brackets");
    if (!std::all_of(address.host.begin(), address.host.end(), IsHostChar)) {
      fail("the host is an address or a host name");
    }
  }
  if (!AllDigits(port) || port.size() > 5 || std::stoul(std::string(port)) > 65535) {
    fail("the port is 0 to 65535");
  }
  address.port = static_cast<std::uint16_t>(std::stoul(std::string(port)));
  return address;
}

}  // namespace evoslam
