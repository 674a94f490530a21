// What a client may reach on the coordinator: only its own job's files, only its own jobs, only
// its share of the storage; and a coordinator without CURVE stays on the loopback interface.

#include <string>
#include <utility>
#include <vector>

#include "common/util/sha256.h"
#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

// A map_server YAML naming `image`.
std::string MapYaml(const std::string& image) {
  return "image: " + image +
         "\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
         "free_thresh: 0.196\n";
}

// ---- Path traversal ----

TEST_F(ServiceTest, AMapNamingAFileOutsideItsJobIsRefusedAtSubmit) {
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker", c.workers);
  evoslam::ServiceClient client = Client(c.clients);
  // A private image on the coordinator's host, and the name of one that does not exist.
  const fs::path secret = Path("secret.pgm");
  std::ofstream(secret) << "P2\n2 1\n255\n0 0\n";
  const std::string missing = Path("missing.pgm");
  const proto::DatasetRef log = client.Upload(Log());
  const proto::DatasetRef own = client.UploadBytes("own.pgm", "P2\n2 1\n255\n0 255\n");

  const std::vector<std::string> variants = {
      secret.string(),   missing,          "../secret.pgm",
      "a/../../x.pgm",   "./own.pgm",      "%2e%2e%2fsecret.pgm",
      "~/secret.pgm",    "\"/etc/x.pgm\"", "/proc/self/root" + secret.string(),
      "own.pgm/../x.pgm"};
  std::vector<std::string> messages;
  for (const std::string& image : variants) {
    const proto::DatasetRef yaml = client.UploadBytes("map.yaml", MapYaml(image));
    proto::JobSpec spec = SpecFor(Job{.scans = 3}, log, yaml, Log(), "map.yaml");
    *spec.mutable_map_image() = own;
    const ProtocolError e = RefusalOf([&] { client.Submit(spec); }, image);
    EXPECT_EQ(e.code(), proto::ERROR_CODE_INVALID) << image << ": " << e.what();
    std::string message = e.what();
    EXPECT_NE(message.find("must be the one uploaded with the job"), std::string::npos) << message;
    if (const auto at = message.find(image); at != std::string::npos) {
      message.replace(at, image.size(), "IMAGE");
    }
    messages.push_back(message);
  }
  // Whether the path exists on the coordinator's disk makes no difference to the answer.
  EXPECT_EQ(messages[0], messages[1]);
  // A map that names no image of its own names nothing it may read.
  const proto::DatasetRef yaml = client.UploadBytes("map.yaml", MapYaml("own.pgm"));
  const proto::JobSpec alone = SpecFor(Job{.scans = 3}, log, yaml, Log(), "map.yaml");
  EXPECT_EQ(RefusalOf([&] { client.Submit(alone); }, "no image").code(), proto::ERROR_CODE_INVALID);
  EXPECT_TRUE(client.Jobs().empty());
  EXPECT_TRUE(c.process->Alive());
}

// ---- Job ownership ----

// Asks whether the coordinator holds `content` for this client, by its hash alone.
bool Holds(evoslam::ServiceClient& client, const std::string& content) {
  proto::ClientRequest ask;
  ask.mutable_upload()->set_name("probe");
  ask.mutable_upload()->set_sha256(evoslam::Sha256Hex(content));
  try {
    return client.Call(ask).stored().already_present();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_UNKNOWN_DATASET) << e.what();
    return false;
  }
}

TEST_F(ServiceTest, WithCurveAClientSeesOnlyItsOwnJobsAndAnAdminSeesAll) {
  const std::string keys = Path("keys");
  for (const char* name : {"coordinator", "worker", "alice", "bob", "admin"}) {
    const CommandResult k = Cli({"keygen", "--name", name, "--out", keys});
    ASSERT_EQ(k.exit_code, 0) << k.output;
  }
  const auto key = [&](const std::string& file) { return keys + "/" + file; };
  const CoordinatorProcess c = StartCoordinator(
      "coordinator",
      {"--curve-secret-key", key("coordinator.key"), "--client-keys", key("alice.pub"),
       key("bob.pub"), "--worker-keys", key("worker.pub"), "--admin-keys", key("admin.pub")});
  const auto client = [&](const std::string& name) {
    evoslam::ClientOptions options;
    options.endpoint = c.clients;
    options.timeout_seconds = 10;
    options.curve = evoslam::LoadCurveClientKeys(key("coordinator.pub"), key(name + ".key"));
    return evoslam::ServiceClient(context_, options);
  };
  evoslam::ServiceClient alice = client("alice"), bob = client("bob"), admin = client("admin");

  // Alice's job waits for a worker while Bob tries it.
  const Job job{.scans = Scans(20)};
  const proto::DatasetRef log = alice.Upload(Log()), map = alice.Upload(Map());
  const std::string id = alice.Submit(SpecFor(job, log, map, Log(), Map()));
  const std::string other = alice.Submit(SpecFor(job, log, map, Log(), Map()));
  EXPECT_TRUE(std::regex_match(id, std::regex("job-[0-9a-f]{32}"))) << id;
  EXPECT_NE(id, other);

  const auto expect_unknown = [&](auto call, const std::string& what) {
    EXPECT_EQ(RefusalOf(call, what).code(), proto::ERROR_CODE_UNKNOWN_JOB) << what;
  };
  EXPECT_TRUE(bob.Jobs().empty());
  expect_unknown([&] { bob.Status(id); }, "status");
  expect_unknown([&] { bob.Cancel(id); }, "cancel");
  expect_unknown([&] { bob.Result(id); }, "result");
  expect_unknown([&] { bob.Watch(id, [](const proto::ProgressEvent&) {}); }, "watch");
  // As the command line says it: the same as for a job that does not exist.
  const std::vector<std::string> as_bob = {"--coordinator",      c.clients,
                                           "--curve-server-key", key("coordinator.pub"),
                                           "--curve-key",        key("bob.key")};
  for (const char* command : {"status", "cancel", "result"}) {
    std::vector<std::string> args = {command, id};
    if (std::string(command) == "result") args.insert(args.end(), {"--out", Path("stolen")});
    args.insert(args.end(), as_bob.begin(), as_bob.end());
    const CommandResult r = Cli(args);
    EXPECT_NE(r.exit_code, 0) << command << ": " << r.output;
    EXPECT_NE(r.output.find("no job " + id), std::string::npos) << command << ": " << r.output;
  }
  std::vector<std::string> jobs_as_bob = {"jobs"};
  jobs_as_bob.insert(jobs_as_bob.end(), as_bob.begin(), as_bob.end());
  const CommandResult listed = Cli(jobs_as_bob);
  EXPECT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_EQ(listed.output.find("job-"), std::string::npos) << listed.output;
  EXPECT_FALSE(fs::exists(Path("stolen")));
  // Nor can Bob use Alice's datasets without their bytes: he cannot tell they are here.
  EXPECT_FALSE(Holds(bob, ReadAll(Log())));
  EXPECT_TRUE(Holds(alice, ReadAll(Log())));
  EXPECT_EQ(
      RefusalOf([&] { bob.Submit(SpecFor(job, log, map, Log(), Map())); }, "bob's submit").code(),
      proto::ERROR_CODE_UNKNOWN_DATASET);

  // An admin sees and may cancel every job.
  ASSERT_EQ(admin.Jobs().size(), 2u);
  EXPECT_EQ(admin.Cancel(other).state(), proto::JOB_STATE_CANCELLED);
  StartWorker("worker", c.workers,
              {"--curve-server-key", key("coordinator.pub"), "--curve-key", key("worker.key")});
  EXPECT_EQ(WaitForEnd(alice, id).state(), proto::JOB_STATE_SUCCEEDED);
  EXPECT_FALSE(admin.Result(id).empty());
  EXPECT_FALSE(alice.Result(id).empty());
  EXPECT_EQ(alice.Status(other).state(), proto::JOB_STATE_CANCELLED);
  EXPECT_EQ(alice.Jobs().size(), 2u);
  EXPECT_TRUE(bob.Jobs().empty());
  expect_unknown([&] { bob.Result(id); }, "result once finished");
}

// ---- Quotas and retention ----

TEST_F(ServiceTest, AClientOverItsQuotaIsToldSoAndTheServiceGoesOn) {
  const std::string log = ReadAll(Log());
  // Room for half the log.
  const double quota_mb = static_cast<double>(log.size()) / 2 / (1 << 20);
  const CoordinatorProcess c =
      StartCoordinator("coordinator", {"--client-quota-mb", std::to_string(quota_mb)});
  const CommandResult r = Cli(RemoteArgs(Job{.scans = 3}, Path("out"), c.clients));
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("over its quota"), std::string::npos) << r.output;
  EXPECT_TRUE(c.process->Alive());
  evoslam::ServiceClient client = Client(c.clients);
  const ProtocolError e = RefusalOf([&] { client.UploadBytes("log.clf", log); }, "upload");
  EXPECT_EQ(e.code(), proto::ERROR_CODE_QUOTA_EXCEEDED) << e.what();
  // What fits is still stored, and the rest of the service answers.
  EXPECT_NO_THROW(client.UploadBytes("small.bin", log.substr(0, log.size() / 4)));
  EXPECT_NO_THROW(client.UploadBytes("small.bin", log.substr(0, log.size() / 4)));  // again: free
  EXPECT_EQ(
      RefusalOf([&] { client.UploadBytes("more.bin", log.substr(0, log.size() / 3)); }, "over")
          .code(),
      proto::ERROR_CODE_QUOTA_EXCEEDED);
  EXPECT_TRUE(client.Jobs().empty());
}

TEST_F(ServiceTest, RetentionCollectsADatasetNoJobReads) {
  // 1.8 s of retention; the coordinator collects every second.
  const CoordinatorProcess c = StartCoordinator("coordinator", {"--retention-hours", "0.0005"});
  evoslam::ServiceClient client = Client(c.clients);
  const std::string unused = "bytes no job will read";
  client.UploadBytes("unused.bin", unused);
  // A job that waits for a worker reads its log and map: they stay.
  const proto::DatasetRef log = client.Upload(Log()), map = client.Upload(Map());
  const std::string id = client.Submit(SpecFor(Job{.scans = 3}, log, map, Log(), Map()));
  EXPECT_TRUE(WaitUntil(
      [&] { return c.process->Log().find("1 unused dataset") != std::string::npos; }, 30s))
      << c.process->Log();
  EXPECT_FALSE(Holds(client, unused));
  EXPECT_TRUE(Holds(client, ReadAll(Log())));
  EXPECT_TRUE(Holds(client, ReadAll(Map())));
  EXPECT_FALSE(Finished(client.Status(id)));
}

// ---- CURVE off ----

TEST_F(ServiceTest, WithoutCurveOnlyLoopbackIsServedUnlessInsecure) {
  for (const auto& [clients, workers] : std::vector<std::pair<std::string, std::string>>{
           {"tcp://0.0.0.0:*", "tcp://127.0.0.1:*"}, {"tcp://127.0.0.1:*", "tcp://*:*"}}) {
    ChildProcess& refused = Start({EVOSLAM_COORDINATOR, "--db", Path("refused.db"), "--clients",
                                   clients, "--workers", workers},
                                  "refused.log");
    const auto status = refused.Wait(20s);
    ASSERT_TRUE(status) << refused.Log();
    EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 2) << refused.Log();
    EXPECT_NE(refused.Log().find("refusing to listen on"), std::string::npos) << refused.Log();
    EXPECT_NE(refused.Log().find("without CURVE"), std::string::npos) << refused.Log();
  }
  // Given --insecure it serves, and warns.
  const CoordinatorProcess c =
      StartCoordinator("coordinator", {"--insecure"}, "tcp://0.0.0.0:*", "tcp://0.0.0.0:*");
  EXPECT_NE(c.process->Log().find("without CURVE (--insecure)"), std::string::npos)
      << c.process->Log();
  evoslam::ServiceClient client = Client(c.clients);
  EXPECT_TRUE(client.Jobs().empty());

  // local-cluster.sh refuses the same before it starts anything.
  for (const char* variable :
       {"EVOSLAM_CLIENTS=tcp://0.0.0.0:5555", "EVOSLAM_WORKERS=tcp://*:5556"}) {
    ChildProcess script(
        {"/bin/bash", EVOSLAM_LOCAL_CLUSTER, "start", "1"}, Path("script.log"),
        {variable, "EVOSLAM_RUN_DIR=" + Path("cluster"),
         "EVOSLAM_BIN=" + fs::path(EVOSLAM_COORDINATOR).parent_path().parent_path().string()});
    const auto status = script.Wait(20s);
    ASSERT_TRUE(status) << script.Log();
    EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 2) << script.Log();
    EXPECT_NE(script.Log().find("CURVE is off"), std::string::npos) << script.Log();
    EXPECT_FALSE(fs::exists(Path("cluster") + "/coordinator.pid"));
  }
}

}  // namespace
}  // namespace evoslam::service_test
