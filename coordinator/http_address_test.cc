#include "coordinator/http_address.h"

#include <gtest/gtest.h>

#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(HttpAddressTest, ReadsHostAndPort) {
  const HttpAddress v4 = ParseHttpAddress("127.0.0.1:9464");
  EXPECT_EQ(v4.host, "127.0.0.1");
  EXPECT_EQ(v4.port, 9464);
  EXPECT_EQ(v4.ToString(), "127.0.0.1:9464");
  const HttpAddress v6 = ParseHttpAddress("[::1]:0");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 0);
  EXPECT_EQ(v6.ToString(), "[::1]:0");
  EXPECT_EQ(ParseHttpAddress("metrics-host.example.org:65535").host, "metrics-host.example.org");
}

TEST(HttpAddressTest, OnlyLoopbackAddressesAreLocal) {
  for (const char* local : {"127.0.0.1:9464", "127.8.9.1:1", "localhost:9464", "[::1]:9464"}) {
    EXPECT_TRUE(ParseHttpAddress(local).IsLoopback()) << local;
  }
  for (const char* open : {"0.0.0.0:9464", "10.0.0.1:9464", "[::]:9464", "example.org:9464",
                           "127.0.0.1.example.org:9464"}) {
    EXPECT_FALSE(ParseHttpAddress(open).IsLoopback()) << open;
  }
}

// Each mistake is told apart, with an example of a right address.
TEST(HttpAddressTest, AMalformedAddressSaysWhatIsWrong) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "no port"},
      {"9464", "no host"},
      {"localhost", "no port"},
      {":9464", "no host"},
      {"127.0.0.1:", "the port is 0 to 65535"},
      {"127.0.0.1:65536", "the port is 0 to 65535"},
      {"127.0.0.1:94x", "the port is 0 to 65535"},
      {"127.0.0.1:-1", "the port is 0 to 65535"},
      {"127.0.0.1:1234567", "the port is 0 to 65535"},
      {"http://127.0.0.1:9464", "without a scheme"},
      {"::1:9464", "an IPv6 address goes in brackets"},
      {"[::1]9464", "in brackets, then a colon"},
      {"[::1", "in brackets, then a colon"},
      {"[]:9464", "the brackets hold an IPv6 address"},
      {"[eth0]:9464", "the brackets hold an IPv6 address"},
      {"host name:9464", "the host is an address or a host name"},
      {"127.0.0.1/metrics:9464", "the host is an address or a host name"},
  };
  for (const auto& [text, why] : cases) {
    try {
      ParseHttpAddress(text);
      ADD_FAILURE() << text << ": accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(why), std::string::npos) << text << ": " << message;
      EXPECT_NE(message.find("e.g. 127.0.0.1:9464"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace evoslam
