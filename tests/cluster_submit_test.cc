// A submit is one job however often it is sent: a client whose answer is lost sends it again
// under the same submit id and gets the job the first send made.

#include <future>
#include <string>
#include <vector>

#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

TEST_F(ServiceTest, ASubmitRetriedAfterATimeoutMakesOneJob) {
  const CoordinatorProcess c = StartCoordinator("coordinator");
  evoslam::ServiceClient client = Client(c.clients, 2);
  const proto::DatasetRef log = client.Upload(Log()), map = client.Upload(Map());
  const proto::JobSpec spec = SpecFor(Job{.scans = 3}, log, map, Log(), Map());
  // Stopped for 3 s, the coordinator leaves the submit unanswered past the client's timeout of
  // 2 s: the client sends it again, and once continued the coordinator reads both sends.
  ASSERT_TRUE(c.process->Kill(SIGSTOP));
  auto submitted = std::async(std::launch::async, [&] { return client.Submit(spec); });
  std::this_thread::sleep_for(3s);
  ASSERT_TRUE(c.process->Kill(SIGCONT));
  std::string id;
  ASSERT_NO_THROW(id = submitted.get());
  EXPECT_TRUE(std::regex_match(id, std::regex("job-[0-9a-f]{32}"))) << id;
  EXPECT_TRUE(WaitUntil(
      [&] { return c.process->Log().find(id + ": submitted again") != std::string::npos; }, 10s))
      << "the second send never reached the coordinator";
  const CommandResult jobs = Cli({"jobs", "--coordinator", c.clients, "--timeout", "10"});
  ASSERT_EQ(jobs.exit_code, 0) << jobs.output;
  EXPECT_EQ(Count(jobs.output, "job-"), 1u) << jobs.output;
  EXPECT_NE(jobs.output.find(id), std::string::npos) << jobs.output;
}

// A submit id names one job of the client that chose it: the same id with the same spec is that
// job, with another spec a mistake; another client's same id is another job.
TEST_F(ServiceTest, ASubmitIdNamesOneJobOfItsClient) {
  const std::string keys = Path("keys");
  for (const char* name : {"coordinator", "worker", "alice", "bob"}) {
    const CommandResult k = Cli({"keygen", "--name", name, "--out", keys});
    ASSERT_EQ(k.exit_code, 0) << k.output;
  }
  const CoordinatorProcess c =
      StartCoordinator("coordinator", {"--curve-secret-key", keys + "/coordinator.key",
                                       "--client-keys", keys + "/alice.pub", keys + "/bob.pub",
                                       "--worker-keys", keys + "/worker.pub"});
  const auto client_of = [&](const std::string& name) {
    evoslam::ClientOptions options;
    options.endpoint = c.clients;
    options.timeout_seconds = 10;
    options.curve =
        evoslam::LoadCurveClientKeys(keys + "/coordinator.pub", keys + "/" + name + ".key");
    return evoslam::ServiceClient(context_, options);
  };
  evoslam::ServiceClient alice = client_of("alice"), bob = client_of("bob");
  const auto spec_of = [&](evoslam::ServiceClient& client, std::uint64_t seed) {
    const proto::DatasetRef log = client.Upload(Log()), map = client.Upload(Map());
    return SpecFor(Job{.scans = 3, .seed = seed}, log, map, Log(), Map());
  };

  const proto::JobSpec spec = spec_of(alice, 1);
  const std::string id = alice.Submit(spec, "nightly-1");
  EXPECT_EQ(alice.Submit(spec, "nightly-1"), id);
  const ProtocolError reused =
      RefusalOf([&] { alice.Submit(spec_of(alice, 2), "nightly-1"); }, "another spec");
  EXPECT_EQ(reused.code(), proto::ERROR_CODE_INVALID) << reused.what();
  EXPECT_NE(std::string(reused.what())
                .find("submit id nightly-1 already made " + id + " with another spec"),
            std::string::npos)
      << reused.what();
  for (const std::string& bad : {std::string(129, 'x'), std::string("two words")}) {
    EXPECT_EQ(RefusalOf([&] { alice.Submit(spec, bad); }, bad).code(), proto::ERROR_CODE_INVALID);
  }
  // A cancelled job is still the job its submit id made.
  EXPECT_EQ(alice.Cancel(id).state(), proto::JOB_STATE_CANCELLED);
  EXPECT_EQ(alice.Submit(spec, "nightly-1"), id);
  ASSERT_EQ(alice.Jobs().size(), 1u);

  const std::string bobs = bob.Submit(spec_of(bob, 1), "nightly-1");
  EXPECT_NE(bobs, id);
  ASSERT_EQ(bob.Jobs().size(), 1u);
  EXPECT_EQ(bob.Jobs()[0].job_id(), bobs);
  EXPECT_EQ(alice.Jobs().size(), 1u);
}

}  // namespace
}  // namespace evoslam::service_test
