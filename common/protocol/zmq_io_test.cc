#include "common/protocol/zmq_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

using ::testing::HasSubstr;

// What ZeroMQ throws for a bad endpoint says neither which endpoint nor what it was for.
TEST(ZmqIoTest, ABadEndpointIsAnErrorNamingItAndWhatItWasFor) {
  zmq::context_t context;
  zmq::socket_t dealer(context, zmq::socket_type::dealer);
  try {
    Connect(dealer, "garbage", "the coordinator");
    ADD_FAILURE() << "connected to 'garbage'";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot connect to the coordinator at garbage: "));
  }
  zmq::socket_t router(context, zmq::socket_type::router);
  try {
    Bind(router, "nosuch://x", "workers");
    ADD_FAILURE() << "bound to 'nosuch://x'";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot listen for workers on nosuch://x: "));
  }
  // A good endpoint binds and is connected to.
  Bind(router, "inproc://zmq-io-test", "workers");
  Connect(dealer, "inproc://zmq-io-test", "the coordinator");
  ASSERT_TRUE(Send(dealer, "hello"));
  zmq::pollitem_t item{router.handle(), 0, ZMQ_POLLIN, 0};
  ASSERT_EQ(zmq::poll(&item, 1, std::chrono::seconds(5)), 1);
  const auto frames = ReceiveFrames(router);
  ASSERT_TRUE(frames);
  ASSERT_EQ(frames->size(), 2u);
  EXPECT_EQ(Text(frames->back()), "hello");
}

TEST(ZmqIoTest, OnlyLoopbackEndpointsCountAsLocal) {
  for (const char* local : {"tcp://127.0.0.1:5555", "tcp://127.8.9.1:*", "tcp://localhost:5555",
                            "tcp://[::1]:5555", "ipc:///tmp/evoslam.sock", "inproc://x"}) {
    EXPECT_TRUE(IsLoopbackEndpoint(local)) << local;
  }
  for (const char* open :
       {"tcp://0.0.0.0:5555", "tcp://*:5555", "tcp://10.0.0.1:5555", "tcp://[::]:5555",
        "tcp://eth0:5555", "tcp://example.org:5555", "tcp://127.0.0.1.example.org:5555",
        "tcp://127.0.0.1", "udp://x:1", "tcp://[::ffff:10.0.0.1]:5555"}) {
    EXPECT_FALSE(IsLoopbackEndpoint(open)) << open;
  }
}

}  // namespace
}  // namespace evoslam
