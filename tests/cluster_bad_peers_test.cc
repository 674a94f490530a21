// Peers that send garbage, answer for tasks they do not hold, or hold no key the coordinator
// lists: each is refused or ignored, and the service goes on serving.

#include <random>
#include <string>
#include <vector>

#include "common/util/sha256.h"
#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

// Sends `frames` and expects an ErrorReply with `code`; returns it.
proto::ClientReply ExpectRefused(RawDealer& raw, const std::vector<std::string>& frames,
                                 proto::ErrorCode code, const std::string& what) {
  raw.Send(frames);
  const auto reply = raw.Receive(10s);
  if (!reply) {
    ADD_FAILURE() << what << ": no answer";
    return {};
  }
  EXPECT_EQ(reply->size(), 1u) << what;
  const std::string& frame = reply->front();
  const proto::ClientReply decoded = evoslam::DecodeClientReply(AsBytes(frame));
  EXPECT_TRUE(decoded.has_error()) << what;
  EXPECT_EQ(decoded.error().code(), code) << what << ": " << decoded.error().message();
  return decoded;
}

std::string RandomBytes(std::mt19937& rng, std::size_t size) {
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  return bytes;
}

TEST_F(ServiceTest, TheClientSocketAnswersBadInputWithTheRightErrorCodes) {
  const CoordinatorProcess c = StartCoordinator("coordinator", {"--max-message-mb", "1"});
  StartWorker("worker1", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 1);
  RawDealer raw(context_, c.clients);

  proto::ClientRequest status;
  status.set_request_id(7);
  status.mutable_status()->set_job_id("job-123456789");
  const std::string valid = evoslam::Encode(status);
  // Cut inside the job id, the last field: the rest can no longer be parsed.
  ExpectRefused(raw, {valid.substr(0, valid.size() - 3)}, proto::ERROR_CODE_MALFORMED,
                "a truncated frame");
  // The valid frame itself is answered, by its id: the socket still works.
  {
    raw.Send({valid});
    const auto reply = raw.Receive(10s);
    ASSERT_TRUE(reply);
    const proto::ClientReply r = evoslam::DecodeClientReply(AsBytes(reply->front()));
    EXPECT_EQ(r.request_id(), 7u);
    EXPECT_EQ(r.error().code(), proto::ERROR_CODE_UNKNOWN_JOB);
  }

  std::mt19937 rng(20261201);
  for (int i = 0; i < 20; ++i) {
    raw.Send({RandomBytes(rng, 1 + rng() % 300)});
    const auto reply = raw.Receive(10s);
    ASSERT_TRUE(reply) << "random frame " << i << ": no answer";
    const proto::ClientReply r = evoslam::DecodeClientReply(AsBytes(reply->front()));
    ASSERT_TRUE(r.has_error()) << "random frame " << i;
    // Bytes that happen to parse carry no version, or a wrong one.
    EXPECT_TRUE(r.error().code() == proto::ERROR_CODE_MALFORMED ||
                r.error().code() == proto::ERROR_CODE_BAD_VERSION)
        << "random frame " << i << ": " << r.error().message();
  }

  proto::ClientRequest big;
  big.set_request_id(8);
  big.mutable_chunk()->set_upload_id("upload-0");
  big.mutable_chunk()->set_content(std::string(std::size_t{3} << 19, 'x'));  // 1.5 MiB
  ExpectRefused(raw, {evoslam::Encode(big)}, proto::ERROR_CODE_TOO_LARGE,
                "a frame over --max-message-mb 1");

  proto::ClientRequest future;
  future.set_protocol_version(evoslam::kProtocolVersion + 1);
  future.set_request_id(9);
  future.mutable_jobs();
  const proto::ClientReply version =
      ExpectRefused(raw, {future.SerializeAsString()}, proto::ERROR_CODE_BAD_VERSION, "version 2");
  EXPECT_NE(version.error().message().find(std::to_string(evoslam::kProtocolVersion + 1)),
            std::string::npos)
      << version.error().message();
  ExpectRefused(raw, {""}, proto::ERROR_CODE_BAD_VERSION, "an empty frame");

  proto::ClientRequest jobs;
  jobs.set_request_id(10);
  jobs.mutable_jobs();
  ExpectRefused(raw, {evoslam::Encode(jobs), "x", "y"}, proto::ERROR_CODE_MALFORMED,
                "a message of 3 frames");
  proto::ClientRequest nothing;
  nothing.set_request_id(11);
  ExpectRefused(raw, {evoslam::Encode(nothing)}, proto::ERROR_CODE_MALFORMED,
                "an envelope with no request");

  proto::ClientRequest mismatch;
  mismatch.set_request_id(12);
  mismatch.mutable_upload()->set_name("log.clf");
  mismatch.mutable_upload()->set_sha256(evoslam::Sha256Hex("other bytes"));
  mismatch.mutable_upload()->set_size_bytes(11);
  raw.Send({evoslam::Encode(mismatch)});
  const auto started = raw.Receive(10s);
  ASSERT_TRUE(started);
  const proto::ClientReply start = evoslam::DecodeClientReply(AsBytes(started->front()));
  ASSERT_TRUE(start.has_upload_started()) << start.DebugString();
  proto::ClientRequest bytes;
  bytes.set_request_id(13);
  bytes.mutable_chunk()->set_upload_id(start.upload_started().upload_id());
  bytes.mutable_chunk()->set_content("these bytes");
  const proto::ClientReply hash =
      ExpectRefused(raw, {evoslam::Encode(bytes)}, proto::ERROR_CODE_INVALID, "a wrong hash");
  EXPECT_EQ(hash.request_id(), 13u);

  // Submits: of datasets never uploaded, and with parameters that cannot work.
  proto::DatasetRef ghost;
  ghost.set_sha256(evoslam::Sha256Hex("never uploaded"));
  ghost.set_name("ghost.clf");
  const proto::DatasetRef map = client.Upload(Map());
  proto::ClientRequest unknown;
  unknown.set_request_id(13);
  *unknown.mutable_submit()->mutable_spec() = SpecFor(Job{}, ghost, map, Log(), Map());
  ExpectRefused(raw, {evoslam::Encode(unknown)}, proto::ERROR_CODE_UNKNOWN_DATASET,
                "a dataset never uploaded");

  const proto::DatasetRef log = client.Upload(Log());
  proto::ClientRequest bad;
  bad.set_request_id(14);
  *bad.mutable_submit()->mutable_spec() = SpecFor(Job{}, log, map, Log(), Map());
  bad.mutable_submit()->mutable_spec()->mutable_localize()->set_generations(0);
  ExpectRefused(raw, {evoslam::Encode(bad)}, proto::ERROR_CODE_INVALID, "zero generations");
  bad.mutable_submit()->mutable_spec()->mutable_localize()->set_fitness("f9");
  ExpectRefused(raw, {evoslam::Encode(bad)}, proto::ERROR_CODE_INVALID, "fitness f9");
  EXPECT_TRUE(client.Jobs().empty()) << "a refused submit left a job behind";
  EXPECT_TRUE(c.process->Alive());

  // Far over the limit, ZeroMQ drops the connection before the memory is spent: no answer, and
  // the coordinator goes on.
  {
    RawDealer flood(context_, c.clients);
    flood.Send({std::string(std::size_t{3} << 20, 'x')});
    EXPECT_FALSE(flood.Receive(1s));
  }
  EXPECT_TRUE(c.process->Alive());

  const Job job{.scans = Scans(20)};
  const CommandResult r = Cli(RemoteArgs(job, Path("after"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(job), Path("after"));
  EXPECT_TRUE(c.process->Alive());
}

TEST_F(ServiceTest, TheWorkerSocketDropsGarbageAndTheServiceGoesOn) {
  const CoordinatorProcess c = StartCoordinator("coordinator", {"--max-message-mb", "1"});
  {
    RawDealer raw(context_, c.workers);
    proto::WorkerMessage ready;
    ready.mutable_ready()->set_hostname("a-host-name-long-enough-to-cut");
    ready.mutable_ready()->set_threads(4);
    const std::string valid = evoslam::Encode(ready);
    raw.Send({valid.substr(0, valid.size() - 5)});
    std::mt19937 rng(7);
    for (int i = 0; i < 20; ++i) raw.Send({RandomBytes(rng, 1 + rng() % 300)});
    proto::WorkerMessage big;
    big.mutable_disconnect()->set_reason(std::string(std::size_t{3} << 19, 'x'));  // 1.5 MiB
    raw.Send({evoslam::Encode(big)});
    proto::WorkerMessage future = ready;
    future.set_protocol_version(evoslam::kProtocolVersion + 1);
    raw.Send({future.SerializeAsString()});
    raw.Send({valid, "x", "y"});
    raw.Send({""});
    // Well-formed, but from a worker that never said Ready: a result for a task it was never
    // given, and a fetch.
    proto::WorkerMessage result;
    result.mutable_result()->set_task_id("t-1");
    result.mutable_result()->mutable_error()->set_message("made up");
    raw.Send({evoslam::Encode(result)});
    proto::WorkerMessage fetch;
    fetch.mutable_fetch()->set_sha256(evoslam::Sha256Hex("never uploaded"));
    raw.Send({evoslam::Encode(fetch)});

    // Each was read and dropped, the unknown worker told to say Ready first.
    const std::string ahead =
        "speaks protocol version " + std::to_string(evoslam::kProtocolVersion + 1);
    for (const std::string& said :
         {std::string("is not a valid protocol buffer"), std::string("is over the limit"), ahead,
          std::string("dropped a message of 4 frames"),
          std::string("dropped a late answer for t-1")}) {
      EXPECT_TRUE(WaitUntil([&] { return c.process->Log().find(said) != std::string::npos; }, 10s))
          << "the coordinator's log never says '" << said << "'";
    }
    bool told = false;
    while (auto frames = raw.Receive(1s)) {
      const std::string& f = frames->front();
      told |= evoslam::DecodeCoordinatorMessage(AsBytes(f)).has_disconnect();
    }
    EXPECT_TRUE(told) << "an unknown worker was not asked to say Ready";
  }
  EXPECT_TRUE(c.process->Alive());
  {
    RawDealer flood(context_, c.workers);
    flood.Send({std::string(std::size_t{3} << 20, 'x')});
    std::this_thread::sleep_for(500ms);
  }
  EXPECT_TRUE(c.process->Alive());

  StartWorker("worker1", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 1);
  const Job job{.scans = Scans(20)};
  const CommandResult r = Cli(RemoteArgs(job, Path("after"), c.clients));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(job), Path("after"));
  EXPECT_TRUE(c.process->Alive());
}

// A worker that answers for a task it does not hold, or answers after the coordinator gave its
// task to another, is not listened to: here the answers are failures, which would fail the job
// if they were taken.
TEST_F(ServiceTest, AnswersFromAWorkerThatDoesNotHoldTheTaskAreDropped) {
  SubmittedJob job = SubmitWithNoWorkers({.scans = Scans(20)});
  const auto fake_worker = FakeWorker(job.coordinator.workers);
  RawDealer& fake = *fake_worker;
  const std::optional<proto::Task> task = AwaitTask(fake);
  ASSERT_TRUE(task);
  const auto failure = [](const std::string& task_id) {
    proto::WorkerMessage m;
    m.mutable_result()->set_task_id(task_id);
    m.mutable_result()->mutable_error()->set_message("this answer must not be taken");
    return evoslam::Encode(m);
  };
  const auto logged = [&](const std::string& what) {
    return WaitUntil([&] { return job.coordinator.process->Log().find(what) != std::string::npos; },
                     10s);
  };
  fake.Send({failure("t-999999")});
  EXPECT_TRUE(logged("dropped an answer for t-999999"));
  // Then it falls silent, holding its task, until the coordinator gives up on it.
  EXPECT_TRUE(logged("its task " + task->task_id() + " goes to another"));
  fake.Send({failure(task->task_id())});
  EXPECT_TRUE(logged("dropped a late answer for " + task->task_id()));
  EXPECT_FALSE(Finished(job.client.Status(job.id))) << Describe(job.client.Status(job.id));

  StartWorker("worker1", job.coordinator.workers);
  ExpectSucceedsLike(job.client, job.id, job.reference);
}

// A worker dropped for silence and then woken answers two requests for a new start with two
// Readys: the coordinator's when it dropped it, and the one it gets for the heartbeat it sends
// on waking. The second comes in after the coordinator has handed it a task again; played here
// by a fake worker, it must not take that task back and send another to a busy worker (which
// would refuse it, and the refusal would fail the job).
TEST_F(ServiceTest, ARepeatedReadyDoesNotTakeBackTheTaskOnItsWayToTheWorker) {
  SubmittedJob job = SubmitWithNoWorkers({.scans = Scans(10)});
  RawDealer fake(context_, job.coordinator.workers);
  proto::WorkerMessage ready;
  ready.mutable_ready()->set_hostname("fake");
  ready.mutable_ready()->set_threads(1);
  proto::WorkerMessage heartbeat;
  heartbeat.mutable_heartbeat();
  // The tasks that come within `wait`, while the fake keeps its heartbeats going.
  const auto tasks_within = [&](Clock::duration wait) {
    std::vector<proto::Task> tasks;
    const Clock::time_point until = Clock::now() + wait;
    while (Clock::now() < until) {
      fake.Send({evoslam::Encode(heartbeat)});
      if (auto frames = fake.Receive(50ms)) {
        const auto m = evoslam::DecodeCoordinatorMessage(AsBytes(frames->front()));
        if (m.has_task()) tasks.push_back(m.task());
      }
    }
    return tasks;
  };
  fake.Send({evoslam::Encode(ready)});
  std::vector<proto::Task> first;
  ASSERT_TRUE(WaitUntil(
      [&] {
        first = tasks_within(50ms);
        return !first.empty();
      },
      10s));
  ASSERT_EQ(first.size(), 1u);

  fake.Send({evoslam::Encode(ready)});
  const std::vector<proto::Task> more = tasks_within(1s);
  EXPECT_TRUE(more.empty()) << "a worker that holds " << first[0].task_id() << " was sent "
                            << more.size() << " more, the first " << more[0].task_id();
  const auto workers = job.client.Workers();
  ASSERT_EQ(workers.size(), 1u);
  EXPECT_TRUE(workers[0].busy());
  EXPECT_EQ(workers[0].worker_id(), "w-1") << "a repeated Ready made a new worker";

  // It leaves, handing its task back; a real worker does the job.
  proto::WorkerMessage bye;
  bye.mutable_disconnect()->set_reason("test over");
  bye.mutable_disconnect()->set_handed_back_task_id(first[0].task_id());
  fake.Send({evoslam::Encode(bye)});
  StartWorker("worker1", job.coordinator.workers);
  ExpectSucceedsLike(job.client, job.id, job.reference);
}

// A worker that refuses a task because it is busy (with work the coordinator no longer counts
// on) does not fail the job: the task goes to another worker, and the busy one is asked to
// introduce itself again.
TEST_F(ServiceTest, ABusyWorkersRefusalSendsTheTaskElsewhere) {
  SubmittedJob job = SubmitWithNoWorkers({.scans = Scans(10)});
  const auto fake_worker = FakeWorker(job.coordinator.workers);
  RawDealer& fake = *fake_worker;
  const std::optional<proto::Task> task = AwaitTask(fake);
  ASSERT_TRUE(task);
  proto::WorkerMessage busy;
  busy.mutable_result()->set_task_id(task->task_id());
  busy.mutable_result()->mutable_error()->set_code(proto::ERROR_CODE_QUEUE_FULL);
  busy.mutable_result()->mutable_error()->set_message("worker busy");
  fake.Send({evoslam::Encode(busy)});
  // It is told to start again, and no longer counts as a worker until it does.
  bool told = false;
  ASSERT_TRUE(WaitUntil(
      [&] {
        while (auto frames = fake.Receive(10ms)) {
          told |= evoslam::DecodeCoordinatorMessage(AsBytes(frames->front())).has_disconnect();
        }
        return told;
      },
      10s));
  EXPECT_TRUE(job.client.Workers().empty());

  StartWorker("worker1", job.coordinator.workers);
  ExpectSucceedsLike(job.client, job.id, job.reference);
}

// ---- CURVE ----

TEST_F(ServiceTest, WithCurveOnlyTheListedKeysAreServed) {
  const std::string keys = Path("keys");
  for (const char* name : {"coordinator", "worker", "client", "stranger"}) {
    const CommandResult k = Cli({"keygen", "--name", name, "--out", keys});
    ASSERT_EQ(k.exit_code, 0) << k.output;
  }
  const auto key = [&](const std::string& file) { return keys + "/" + file; };
  const CoordinatorProcess c = StartCoordinator(
      "coordinator", {"--curve-secret-key", key("coordinator.key"), "--client-keys",
                      key("client.pub"), "--worker-keys", key("worker.pub")});
  StartWorker("worker", c.workers,
              {"--curve-server-key", key("coordinator.pub"), "--curve-key", key("worker.key")});
  // A worker whose key is not listed never gets in.
  StartWorker("stranger-worker", c.workers,
              {"--curve-server-key", key("coordinator.pub"), "--curve-key", key("stranger.key")});
  const std::vector<std::string> as_client = {"--coordinator",      c.clients,
                                              "--curve-server-key", key("coordinator.pub"),
                                              "--curve-key",        key("client.key")};
  const auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };

  const Job job{.scans = Scans(20)};
  std::vector<std::string> localize = LocalizeArgs(job, Path("remote"));
  localize.insert(localize.end(), as_client.begin(), as_client.end());
  const CommandResult r = Cli(localize);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameTrajectory(Reference(job), Path("remote"));
  const CommandResult workers = Cli(with({"workers"}, as_client));
  ASSERT_EQ(workers.exit_code, 0) << workers.output;
  EXPECT_EQ(Count(workers.output, " done\n"), 1u) << workers.output;

  // Refused clients hear nothing at all, and say so when their time is up.
  const std::vector<std::pair<std::string, std::vector<std::string>>> refused = {
      {"no CURVE", {"--coordinator", c.clients}},
      {"an unlisted key",
       {"--coordinator", c.clients, "--curve-server-key", key("coordinator.pub"), "--curve-key",
        key("stranger.key")}},
      {"a worker's key",
       {"--coordinator", c.clients, "--curve-server-key", key("coordinator.pub"), "--curve-key",
        key("worker.key")}},
  };
  for (const auto& [what, args] : refused) {
    const CommandResult no = Cli(with(with({"jobs"}, args), {"--timeout", "2"}), 20s);
    EXPECT_NE(no.exit_code, 0) << what << ": " << no.output;
    EXPECT_NE(no.output.find("no answer from the coordinator"), std::string::npos)
        << what << ": " << no.output;
    EXPECT_LT(no.seconds, 2 + 5.0) << what;
    EXPECT_TRUE(c.process->Alive());
  }
  EXPECT_NE(c.process->Log().find("is not accepted"), std::string::npos);

  const CommandResult jobs = Cli(with({"jobs"}, as_client));
  ASSERT_EQ(jobs.exit_code, 0) << jobs.output;
  EXPECT_NE(jobs.output.find("succeeded"), std::string::npos) << jobs.output;
}

}  // namespace
}  // namespace evoslam::service_test
