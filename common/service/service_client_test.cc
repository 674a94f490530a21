#include "common/service/service_client.h"

#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <string>
#include <vector>

#include "common/protocol/wire.h"
#include "common/protocol/zmq_io.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(MapYamlTest, FindsAndReplacesTheImagePath) {
  const std::string yaml = "resolution: 0.05\n  image:  \"maps/lab.pgm\" \norigin: [0, 0, 0]\n";
  EXPECT_EQ(MapYamlImage(yaml), "maps/lab.pgm");
  const std::string moved = WithMapYamlImage(yaml, "lab.pgm");
  EXPECT_EQ(MapYamlImage(moved), "lab.pgm");
  EXPECT_NE(moved.find("resolution: 0.05\n"), std::string::npos);
  EXPECT_NE(moved.find("origin: [0, 0, 0]\n"), std::string::npos);
  EXPECT_FALSE(MapYamlImage("resolution: 0.05\n"));
}

// A coordinator the test plays on an inproc ROUTER socket: it reads client requests and answers
// those it chooses.
class FakeCoordinator {
 public:
  explicit FakeCoordinator(zmq::context_t& context) : router_(context, zmq::socket_type::router) {
    router_.set(zmq::sockopt::linger, 0);
    Bind(router_, kEndpoint, "clients");
  }

  struct Received {
    std::string identity;
    proto::ClientRequest request;
  };
  // The next request within 5 s; nullopt when none comes.
  std::optional<Received> Next() {
    zmq::pollitem_t item{router_.handle(), 0, ZMQ_POLLIN, 0};
    if (zmq::poll(&item, 1, std::chrono::seconds(5)) != 1) return std::nullopt;
    const auto frames = ReceiveFrames(router_);
    if (!frames || frames->size() != 2) return std::nullopt;
    return Received{Text(frames->front()), DecodeClientRequest(Bytes(frames->back()))};
  }
  void Accept(const Received& to, std::uint64_t request_id, const std::string& job_id) {
    proto::ClientReply reply;
    reply.set_request_id(request_id);
    reply.mutable_accepted()->set_job_id(job_id);
    SendTo(router_, to.identity, Encode(reply));
  }

  static constexpr const char* kEndpoint = "inproc://service-client-test";

 private:
  zmq::socket_t router_;
};

ServiceClient ClientOf(zmq::context_t& context, double timeout_seconds, int submit_attempts) {
  ClientOptions options;
  options.endpoint = FakeCoordinator::kEndpoint;
  options.timeout_seconds = timeout_seconds;
  options.submit_attempts = submit_attempts;
  return ServiceClient(context, options);
}

// A submit left unanswered is sent again with the same submit id (under a new request id), and
// the answer to any of its sends, even the first, is its answer.
TEST(ServiceClientTest, AnUnansweredSubmitIsSentAgainUnderTheSameSubmitId) {
  zmq::context_t context;
  FakeCoordinator coordinator(context);
  // Attempts to spare, so that a slow test thread cannot make the client give up.
  ServiceClient client = ClientOf(context, 0.3, 20);
  proto::JobSpec spec;
  spec.set_seed(7);
  auto submitted = std::async(std::launch::async, [&] { return client.Submit(spec); });
  const auto first = coordinator.Next();
  const auto second = coordinator.Next();  // after the client's timeout
  ASSERT_TRUE(first && second);
  const proto::SubmitJob& a = first->request.submit();
  const proto::SubmitJob& b = second->request.submit();
  EXPECT_EQ(a.submit_id().size(), 32u) << a.submit_id();
  EXPECT_EQ(a.submit_id(), b.submit_id());
  EXPECT_EQ(b.spec().seed(), 7u);
  EXPECT_NE(first->request.request_id(), second->request.request_id());
  coordinator.Accept(*first, first->request.request_id(), "job-1");
  EXPECT_EQ(submitted.get(), "job-1");

  // The next submit is another job: another submit id. (Sends of the first that went out
  // before its answer came in are still waiting.)
  submitted = std::async(std::launch::async, [&] { return client.Submit(spec); });
  auto third = coordinator.Next();
  while (third && third->request.submit().submit_id() == a.submit_id()) third = coordinator.Next();
  ASSERT_TRUE(third);
  coordinator.Accept(*third, third->request.request_id(), "job-2");
  EXPECT_EQ(submitted.get(), "job-2");
}

TEST(ServiceClientTest, ASubmitNeverAnsweredFailsAfterItsAttempts) {
  zmq::context_t context;
  FakeCoordinator coordinator(context);
  ServiceClient client = ClientOf(context, 0.1, 3);
  try {
    client.Submit(proto::JobSpec(), "my-id");
    FAIL() << "a submit nobody answered returned";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("within 0.1 s, 3 times"), std::string::npos) << e.what();
  }
  for (int i = 0; i < 3; ++i) {
    const auto sent = coordinator.Next();
    ASSERT_TRUE(sent) << "send " << i + 1;
    EXPECT_EQ(sent->request.submit().submit_id(), "my-id");
  }
}

}  // namespace
}  // namespace evoslam
