#include "coordinator/metrics_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <optional>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

HttpAddress AnyPort() { return ParseHttpAddress("127.0.0.1:0"); }

TEST(MetricsServerTest, ServesMetricsAndNothingElse) {
  std::atomic<int> renders{0};
  MetricsServer server(AnyPort(), [&] {
    ++renders;
    return std::string("evoslam_up 1\n");
  });
  ASSERT_NE(server.address().port, 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.address().port) + "/metrics");
  httplib::Client client(server.address().host, server.address().port);
  const httplib::Result metrics = client.Get("/metrics");
  ASSERT_TRUE(metrics) << httplib::to_string(metrics.error());
  EXPECT_EQ(metrics->status, 200);
  EXPECT_EQ(metrics->body, "evoslam_up 1\n");
  EXPECT_EQ(metrics->get_header_value("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  for (const char* other : {"/", "/metrics/", "/metric", "/favicon.ico"}) {
    const httplib::Result r = client.Get(other);
    ASSERT_TRUE(r) << other;
    EXPECT_EQ(r->status, 404) << other;
  }
  EXPECT_EQ(renders, 1);
}

// A port another server holds is an error naming the address, not a second listener.
TEST(MetricsServerTest, APortTakenIsAClearError) {
  const MetricsServer first(AnyPort(), [] { return std::string(); });
  try {
    const MetricsServer second(first.address(), [] { return std::string(); });
    FAIL() << "two servers listen on " << first.address().ToString();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot serve metrics on " + first.address().ToString()),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("in use"), std::string::npos) << message;
  }
}

// Destroyed at once, before its thread has started listening, it still stops.
TEST(MetricsServerTest, StopsWhenDestroyedAtOnce) {
  for (int i = 0; i < 20; ++i) {
    std::optional<MetricsServer> server;
    server.emplace(AnyPort(), [] { return std::string(); });
    server.reset();
  }
}

}  // namespace
}  // namespace evoslam
