// Datasets travel in chunks, and the coordinator spools, hashes and stores them off its broker
// thread: large uploads during a job hold up neither the job nor the workers' heartbeats, and
// cost the coordinator no more memory than a few chunks. A bad upload is refused and the service
// goes on.

#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/util/sha256.h"
#include "coordinator/job_store.h"
#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

// Writes `bytes` of a pattern drawn from `seed` (xorshift), so that no two files are alike.
void WriteDataset(const fs::path& path, std::size_t bytes, std::uint64_t seed) {
  std::ofstream out(path, std::ios::binary);
  std::vector<std::uint64_t> block(1 << 16);
  std::uint64_t x = seed * 0x9e3779b97f4a7c15ull + 1;
  for (std::size_t written = 0; written < bytes;) {
    for (std::uint64_t& word : block) {
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
      word = x;
    }
    const std::size_t n = std::min(bytes - written, block.size() * sizeof(std::uint64_t));
    out.write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(n));
    written += n;
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The peak resident memory of a running process (VmHWM), in KiB.
long PeakRssKib(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

std::size_t FilesIn(const fs::path& dir) {
  if (!fs::exists(dir)) return 0;
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// Issue 53's case: three clients upload 200 MB each at once while a job runs on two workers whose
// heartbeats are 0.2 s apart (a worker silent for 0.6 s is lost). Under the sanitizers the
// uploads are 20 MB, and the coordinator's memory is not measured (the sanitizers' own
// bookkeeping dwarfs it).
TEST_F(ServiceTest, ThreeLargeUploadsDuringAJobLoseNoWorkerAndKeepTheCoordinatorSmall) {
  constexpr std::size_t kUploadBytes = (std::size_t{200} << 20) / kScaleDown;
  std::vector<fs::path> files;
  std::vector<std::string> hashes;
  for (std::uint64_t i = 0; i < 3; ++i) {
    files.push_back(Path("upload-" + std::to_string(i) + ".bin"));
    WriteDataset(files.back(), kUploadBytes, i + 1);
    hashes.push_back(Sha256HexOfFile(files.back()));
  }
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);
  const Job job{.scans = Scans(200), .optimizer = "island", .islands = 4, .gen = 50};
  const std::string id = SubmitDetached(job, c.clients);
  WaitForProgress(client, id);

  const Clock::time_point start = Clock::now();
  std::mutex mutex;
  std::vector<std::string> errors;
  std::vector<proto::DatasetRef> refs(3);
  std::vector<double> seconds(3);
  // Meanwhile a client asks for the job's status: its answers must not wait for the uploads.
  double slowest_status = 0;
  std::jthread asker([&](const std::stop_token& stop) {
    try {
      auto mine = Client(c.clients, 30);
      while (!stop.stop_requested()) {
        const Clock::time_point asked = Clock::now();
        mine.Status(id);
        slowest_status =
            std::max(slowest_status, std::chrono::duration<double>(Clock::now() - asked).count());
        std::this_thread::sleep_for(100ms);
      }
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex);
      errors.push_back(std::string("status: ") + e.what());
    }
  });
  {
    std::vector<std::jthread> uploaders;
    for (std::size_t i = 0; i < 3; ++i) {
      uploaders.emplace_back([&, i] {
        try {
          // Each waits for its last answer behind the others' stores.
          auto mine = Client(c.clients, 120);
          refs[i] = mine.Upload(files[i]);
          seconds[i] = std::chrono::duration<double>(Clock::now() - start).count();
        } catch (const std::exception& e) {
          std::lock_guard lock(mutex);
          errors.push_back(e.what());
        }
      });
    }
  }
  asker.request_stop();
  asker.join();
  const proto::JobStatus after_uploads = client.Status(id);
  const long peak_kib = PeakRssKib(c.process->pid());
  std::cout << "three uploads of " << kUploadBytes << " bytes took " << seconds[0] << ", "
            << seconds[1] << " and " << seconds[2] << " s; the slowest status answer meanwhile "
            << slowest_status << " s; the coordinator's peak RSS is " << peak_kib / 1024
            << " MiB; the job then: " << Describe(after_uploads) << "\n";
  ASSERT_TRUE(errors.empty()) << errors.front();
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(refs[i].sha256(), hashes[i]);
    EXPECT_EQ(refs[i].size_bytes(), kUploadBytes);
  }

  const proto::JobStatus end = WaitForEnd(client, id);
  EXPECT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
  const std::string log = c.process->Log();
  EXPECT_EQ(log.find("is lost"), std::string::npos) << "a worker was declared lost";
  EXPECT_EQ(log.find("did not run for"), std::string::npos) << "the broker stalled";
  EXPECT_EQ(client.Workers().size(), 2u);
  for (const fs::path& file : files) {
    EXPECT_EQ(Count(log, "stored dataset " + file.string() + " ("), 1u) << file;
  }
  EXPECT_EQ(FilesIn(Path("jobs.db") + "-uploads"), 0u) << "spool files left behind";
#ifndef EVOSLAM_SANITIZED
  EXPECT_LT(slowest_status, 1.0) << "a status request waited for the uploads";
  EXPECT_GT(peak_kib, 0);
  EXPECT_LT(peak_kib, 400 * 1024) << "the coordinator's peak RSS";
#endif
  // What the database holds is the files' bytes.
  evoslam::JobStore store(Path("jobs.db"));
  for (std::size_t i = 0; i < 3; ++i) {
    const auto bytes = store.Dataset(hashes[i]);
    ASSERT_TRUE(bytes) << files[i];
    EXPECT_EQ(evoslam::Sha256Hex(*bytes), hashes[i]) << files[i];
  }
}

// The same bytes from two clients at once: each upload is spooled and hashed on its own, and the
// bytes are stored once, held by both.
TEST_F(ServiceTest, TwoClientsUploadingTheSameBytesAtOnceBothGetThem) {
  const CoordinatorProcess c = StartCoordinator("coordinator");
  const fs::path file = Path("same.bin");
  WriteDataset(file, std::size_t{24} << 20, 7);
  std::vector<proto::DatasetRef> refs(2);
  {
    std::vector<std::jthread> uploaders;
    for (std::size_t i = 0; i < 2; ++i) {
      uploaders.emplace_back([&, i] {
        auto mine = Client(c.clients, 60);
        refs[i] = mine.Upload(file);
      });
    }
  }
  const std::string sha = Sha256HexOfFile(file);
  EXPECT_EQ(refs[0].sha256(), sha);
  EXPECT_EQ(refs[1].sha256(), sha);
  EXPECT_EQ(Count(c.process->Log(), "stored dataset"), 1u) << c.process->Log();
  evoslam::JobStore store(Path("jobs.db"));
  EXPECT_EQ(evoslam::Sha256Hex(store.Dataset(sha).value_or("")), sha);
}

// Refusals, each a clear ErrorReply to the request that caused it; then the service still works.
class UploadRefusalTest : public ServiceTest {
 protected:
  void SetUp() override {
    // Frames of 1 MiB at most make chunks of 512 KiB.
    c_ = StartCoordinator("coordinator", {"--max-message-mb", "1", "--max-dataset-mb", "1",
                                          "--client-quota-mb", "2", "--upload-timeout", "1"});
    raw_ = std::make_unique<RawDealer>(context_, c_.clients);
  }

  proto::ClientReply Ask(proto::ClientRequest request) {
    request.set_request_id(++request_id_);
    raw_->Send({evoslam::Encode(request)});
    const auto reply = raw_->Receive(10s);
    if (!reply) throw std::runtime_error("no answer to request " + std::to_string(request_id_));
    proto::ClientReply decoded = evoslam::DecodeClientReply(AsBytes(reply->front()));
    EXPECT_EQ(decoded.request_id(), request_id_);
    return decoded;
  }

  proto::ClientReply Start(const std::string& name, const std::string& sha, std::uint64_t size) {
    proto::ClientRequest r;
    r.mutable_upload()->set_name(name);
    r.mutable_upload()->set_sha256(sha);
    r.mutable_upload()->set_size_bytes(size);
    return Ask(r);
  }

  // Starts an upload and returns its id.
  std::string Started(const std::string& name, const std::string& content) {
    const proto::ClientReply reply = Start(name, Sha256Hex(content), content.size());
    EXPECT_TRUE(reply.has_upload_started()) << reply.DebugString();
    return reply.upload_started().upload_id();
  }

  proto::ClientReply Send(const std::string& id, std::uint64_t offset, const std::string& bytes) {
    proto::ClientRequest r;
    r.mutable_chunk()->set_upload_id(id);
    r.mutable_chunk()->set_offset(offset);
    r.mutable_chunk()->set_content(bytes);
    return Ask(r);
  }

  static void ExpectRefusal(const proto::ClientReply& reply, proto::ErrorCode code,
                            const std::string& says) {
    ASSERT_TRUE(reply.has_error()) << reply.DebugString();
    EXPECT_EQ(reply.error().code(), code) << reply.error().message();
    EXPECT_NE(reply.error().message().find(says), std::string::npos) << reply.error().message();
  }

  CoordinatorProcess c_;
  std::unique_ptr<RawDealer> raw_;
  std::uint64_t request_id_ = 0;
};

TEST_F(UploadRefusalTest, AChunkOutOfOrderEndsItsUpload) {
  const std::string content(1000, 'a');
  const std::string id = Started("order.bin", content);
  EXPECT_TRUE(Send(id, 0, content.substr(0, 400)).has_chunk_stored());
  ExpectRefusal(Send(id, 800, content.substr(800)), proto::ERROR_CODE_INVALID, "in order");
  ExpectRefusal(Send(id, 400, content.substr(400, 400)), proto::ERROR_CODE_UNKNOWN_UPLOAD,
                "no upload");
  EXPECT_EQ(FilesIn(Path("jobs.db") + "-uploads"), 0u);
}

TEST_F(UploadRefusalTest, BytesPastTheAnnouncedSizeOrOfAnotherHashAreRefused) {
  const std::string content(1000, 'b');
  const std::string id = Started("size.bin", content);
  ExpectRefusal(Send(id, 0, content + "x"), proto::ERROR_CODE_INVALID, "past the announced size");
  proto::ClientReply start = Start("hash.bin", Sha256Hex("other bytes"), content.size());
  ASSERT_TRUE(start.has_upload_started());
  ExpectRefusal(Send(start.upload_started().upload_id(), 0, content), proto::ERROR_CODE_INVALID,
                "hash to " + Sha256Hex(content));
}

TEST_F(UploadRefusalTest, ADatasetOverTheLimitOrTheQuotaIsRefusedBeforeItsBytesTravel) {
  ExpectRefusal(Start("big.bin", Sha256Hex("x"), (1 << 20) + 1), proto::ERROR_CODE_TOO_LARGE,
                "over the limit");
  // Uploads under way count against the quota (2 MiB) as if stored.
  const std::string first(900 << 10, 'c'), second(900 << 10, 'd'), third(900 << 10, 'e');
  const std::string a = Started("first.bin", first);
  Started("second.bin", second);
  ExpectRefusal(Start("third.bin", Sha256Hex(third), third.size()),
                proto::ERROR_CODE_QUOTA_EXCEEDED, "over its quota");
  // The first, finished, is stored; the client's other requests still work.
  proto::ClientReply stored;
  for (std::size_t at = 0; at < first.size(); at += 512 << 10) {
    stored = Send(a, at, first.substr(at, 512 << 10));
  }
  ASSERT_TRUE(stored.has_stored()) << stored.DebugString();
  proto::ClientRequest jobs;
  jobs.mutable_jobs();
  EXPECT_TRUE(Ask(jobs).has_jobs());
}

TEST_F(UploadRefusalTest, AnUploadItsClientAbandonsIsDroppedWithItsSpool) {
  const std::string content(1000, 'f');
  const std::string id = Started("abandoned.bin", content);
  EXPECT_TRUE(Send(id, 0, content.substr(0, 500)).has_chunk_stored());
  EXPECT_EQ(FilesIn(Path("jobs.db") + "-uploads"), 1u);
  EXPECT_TRUE(WaitUntil(
      [&] {
        return c_.process->Log().find(id + " of dataset abandoned.bin is dropped") !=
               std::string::npos;
      },
      10s))
      << c_.process->Log();
  EXPECT_TRUE(WaitUntil([&] { return FilesIn(Path("jobs.db") + "-uploads") == 0; }, 5s));
  ExpectRefusal(Send(id, 500, content.substr(500)), proto::ERROR_CODE_UNKNOWN_UPLOAD, "no upload");
  // Its quota is free again, and a new upload of the same bytes goes through.
  const std::string again = Started("abandoned.bin", content);
  EXPECT_TRUE(Send(again, 0, content).has_stored());
}

TEST_F(UploadRefusalTest, AChunkOverTheChunkSizeIsTooLarge) {
  const std::string content(std::size_t{900} << 10, 'g');
  const proto::ClientReply start = Start("chunky.bin", Sha256Hex(content), content.size());
  ASSERT_TRUE(start.has_upload_started());
  const std::uint64_t chunk = start.upload_started().chunk_bytes();
  ASSERT_LT(chunk, content.size()) << "the chunks fit the frames of --max-message-mb";
  ExpectRefusal(Send(start.upload_started().upload_id(), 0, content.substr(0, chunk + 1)),
                proto::ERROR_CODE_TOO_LARGE, "over the limit");
}

}  // namespace
}  // namespace evoslam::service_test
