#include "coordinator/upload_intake.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>

#include "common/util/sha256.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;

std::string Content(std::size_t size, int seed = 0) {
  std::string bytes(size, '\0');
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>((i * 131 + 17 + seed) % 256);
  return bytes;
}

proto::UploadChunk Chunk(const std::string& id, std::uint64_t offset, std::string content) {
  proto::UploadChunk chunk;
  chunk.set_upload_id(id);
  chunk.set_offset(offset);
  chunk.set_content(std::move(content));
  return chunk;
}

class UploadIntakeTest : public ::testing::Test {
 protected:
  fs::path Db() const { return dir_ / "coordinator.db"; }
  fs::path Spools() const { return dir_ / "uploads"; }

  UploadIntake::Options Small(std::uint64_t quota = 0) const {
    UploadIntake::Options options;
    options.chunk_bytes = 64;
    options.quota_bytes = quota;
    options.quiet = true;
    return options;
  }

  UploadIntake::Deliver Collector() {
    return [this](UploadIntake::Answer answer) {
      {
        std::lock_guard lock(mutex_);
        answers_.push_back(std::move(answer));
      }
      arrived_.notify_all();
    };
  }

  // The next answer, in the order the requests were handed over.
  UploadIntake::Answer Next() {
    std::unique_lock lock(mutex_);
    if (!arrived_.wait_for(lock, std::chrono::seconds(20), [&] { return !answers_.empty(); })) {
      ADD_FAILURE() << "no answer";
      return {};
    }
    UploadIntake::Answer answer = std::move(answers_.front());
    answers_.pop_front();
    return answer;
  }

  // Starts upload `id` of `size` bytes hashing to `sha` for client "c", and waits until it is.
  void Begin(UploadIntake& intake, const std::string& id, const std::string& sha,
             std::size_t size) {
    intake.Start("c", 1, id, id + ".clf", sha, size, "", 0, 10.0);
    EXPECT_TRUE(Next().reply.has_upload_started());
  }

  // Starts upload `id` of `content` and sends it in chunks of 64 bytes, all at once; returns the
  // last answer.
  UploadIntake::Answer Upload(UploadIntake& intake, const std::string& id,
                              const std::string& content, const std::string& owner) {
    intake.Start("client", 1, id, id + ".clf", Sha256Hex(content), content.size(), owner, 0, 10.0);
    EXPECT_TRUE(Next().reply.has_upload_started());
    std::size_t at = 0;
    do {
      intake.Append("client", 2, Chunk(id, at, content.substr(at, 64)));
      at += 64;
    } while (at < content.size());
    UploadIntake::Answer last;
    for (std::size_t sent = 0; sent < (content.size() + 63) / 64 || sent == 0; ++sent) {
      last = Next();
    }
    return last;
  }

  std::size_t SpoolFiles() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(Spools())) ++n;
    return n;
  }

  TempDir dir_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<UploadIntake::Answer> answers_;
};

TEST_F(UploadIntakeTest, AnUploadInChunksIsStoredWholeAndItsSpoolGoes) {
  UploadIntake intake(Db(), Spools(), Small(), Collector());
  const std::string content = Content(1000);
  intake.Start("client", 7, "upload-a", "log.clf", Sha256Hex(content), content.size(), "alice", 0,
               10.0);
  const UploadIntake::Answer started = Next();
  EXPECT_EQ(started.identity, "client");
  EXPECT_EQ(started.reply.request_id(), 7u);
  EXPECT_FALSE(started.ended);
  ASSERT_TRUE(started.reply.has_upload_started());
  EXPECT_EQ(started.reply.upload_started().chunk_bytes(), 64u);
  EXPECT_EQ(started.reply.upload_started().window(), kUploadWindow);
  EXPECT_EQ(SpoolFiles(), 1u);
  for (std::size_t at = 0; at < content.size(); at += 64) {
    intake.Append("client", 8 + at, Chunk("upload-a", at, content.substr(at, 64)));
    const UploadIntake::Answer answer = Next();
    EXPECT_EQ(answer.reply.request_id(), 8 + at);
    EXPECT_EQ(answer.upload_id, "upload-a");
    if (at + 64 < content.size()) {
      ASSERT_TRUE(answer.reply.has_chunk_stored()) << answer.reply.DebugString();
      EXPECT_EQ(answer.reply.chunk_stored().received_bytes(), at + 64);
      EXPECT_FALSE(answer.ended);
    } else {
      ASSERT_TRUE(answer.reply.has_stored()) << answer.reply.DebugString();
      EXPECT_EQ(answer.reply.stored().dataset().sha256(), Sha256Hex(content));
      EXPECT_EQ(answer.reply.stored().dataset().size_bytes(), content.size());
      EXPECT_FALSE(answer.reply.stored().already_present());
      EXPECT_TRUE(answer.ended);
    }
  }
  EXPECT_EQ(SpoolFiles(), 0u);
  JobStore store(Db());
  EXPECT_EQ(store.Dataset(Sha256Hex(content)), content);
  EXPECT_TRUE(store.OwnsDataset(Sha256Hex(content), "alice"));
  EXPECT_EQ(store.StoredBytes("alice"), content.size());
}

TEST_F(UploadIntakeTest, AnEmptyDatasetIsStored) {
  UploadIntake intake(Db(), Spools(), Small(), Collector());
  const UploadIntake::Answer last = Upload(intake, "upload-e", "", "");
  ASSERT_TRUE(last.reply.has_stored()) << last.reply.DebugString();
  EXPECT_EQ(JobStore(Db()).Dataset(Sha256Hex("")), "");
}

// Two clients sending the same bytes at once, chunks interleaved: each upload has its own spool
// and hash, the bytes are stored once, and both clients hold them.
TEST_F(UploadIntakeTest, TwoClientsUploadingTheSameBytesAtOnceBothHoldThem) {
  UploadIntake intake(Db(), Spools(), Small(), Collector());
  const std::string content = Content(300);
  const std::string sha = Sha256Hex(content);
  intake.Start("a", 1, "upload-a", "a.clf", sha, content.size(), "alice", 0, 10.0);
  intake.Start("b", 1, "upload-b", "b.clf", sha, content.size(), "bob", 0, 10.0);
  // Chunks follow the start's answer, as a client's do.
  EXPECT_TRUE(Next().reply.has_upload_started());
  EXPECT_TRUE(Next().reply.has_upload_started());
  for (std::size_t at = 0; at < content.size(); at += 64) {
    intake.Append("a", 2, Chunk("upload-a", at, content.substr(at, 64)));
    intake.Append("b", 2, Chunk("upload-b", at, content.substr(at, 64)));
  }
  int stored = 0, present = 0;
  for (int i = 0; i < 2 * 5; ++i) {
    const UploadIntake::Answer answer = Next();
    EXPECT_FALSE(answer.reply.has_error()) << answer.reply.error().message();
    if (answer.reply.has_stored()) {
      ++stored;
      present += answer.reply.stored().already_present();
    }
  }
  EXPECT_EQ(stored, 2);
  EXPECT_EQ(present, 1);
  JobStore store(Db());
  EXPECT_EQ(store.Dataset(sha), content);
  EXPECT_TRUE(store.OwnsDataset(sha, "alice"));
  EXPECT_TRUE(store.OwnsDataset(sha, "bob"));
}

TEST_F(UploadIntakeTest, AChunkOutOfOrderEndsTheUploadAndTheNextIsOfNoUpload) {
  UploadIntake intake(Db(), Spools(), Small(), Collector());
  const std::string content = Content(300);
  Begin(intake, "upload-x", Sha256Hex(content), content.size());
  intake.Append("c", 2, Chunk("upload-x", 64, content.substr(64, 64)));
  const UploadIntake::Answer refused = Next();
  ASSERT_TRUE(refused.reply.has_error());
  EXPECT_EQ(refused.reply.error().code(), proto::ERROR_CODE_INVALID);
  EXPECT_NE(refused.reply.error().message().find("in order"), std::string::npos)
      << refused.reply.error().message();
  EXPECT_TRUE(refused.ended);
  EXPECT_EQ(SpoolFiles(), 0u);
  intake.Append("c", 3, Chunk("upload-x", 0, content.substr(0, 64)));
  EXPECT_EQ(Next().reply.error().code(), proto::ERROR_CODE_UNKNOWN_UPLOAD);
  EXPECT_FALSE(JobStore(Db()).HasDataset(Sha256Hex(content)));
}

TEST_F(UploadIntakeTest, BytesOfAnotherHashAreRefusedAndNothingIsStored) {
  UploadIntake intake(Db(), Spools(), Small(), Collector());
  const std::string content = Content(100);
  Begin(intake, "upload-x", Sha256Hex("other"), content.size());
  intake.Append("c", 2, Chunk("upload-x", 0, content.substr(0, 64)));
  Next();
  intake.Append("c", 3, Chunk("upload-x", 64, content.substr(64)));
  const UploadIntake::Answer refused = Next();
  EXPECT_EQ(refused.reply.error().code(), proto::ERROR_CODE_INVALID);
  EXPECT_TRUE(refused.ended);
  JobStore store(Db());
  EXPECT_FALSE(store.HasDataset(Sha256Hex(content)));
  EXPECT_FALSE(store.HasDataset(Sha256Hex("other")));
}

// The quota is checked again when the bytes are stored: the client's stored bytes may have grown
// since its upload started (another upload of its, a job's results).
TEST_F(UploadIntakeTest, AnUploadOverTheQuotaWhenItEndsIsRefused) {
  JobStore(Db()).PutDataset(std::string(64, 'a'), "old.clf", Content(100), "alice", 1.0);
  UploadIntake intake(Db(), Spools(), Small(250), Collector());
  const std::string content = Content(100, 1);
  intake.Start("c", 1, "upload-q", "q.clf", Sha256Hex(content), content.size(), "alice", 0, 10.0);
  ASSERT_TRUE(Next().reply.has_upload_started());
  JobStore(Db()).PutDataset(std::string(64, 'b'), "meanwhile.clf", Content(100, 2), "alice", 2.0);
  intake.Append("c", 2, Chunk("upload-q", 0, content.substr(0, 64)));
  intake.Append("c", 3, Chunk("upload-q", 64, content.substr(64)));
  EXPECT_TRUE(Next().reply.has_chunk_stored());
  const UploadIntake::Answer last = Next();
  EXPECT_EQ(last.reply.error().code(), proto::ERROR_CODE_QUOTA_EXCEEDED);
  EXPECT_TRUE(last.ended);
  // Another client has room.
  EXPECT_TRUE(Upload(intake, "upload-r", content, "bob").reply.has_stored());
  EXPECT_EQ(SpoolFiles(), 0u);
}

// The start asks the database, off the broker: bytes the client holds need not travel, a
// question about bytes it does not hold is UNKNOWN_DATASET, and its uploads under way count
// against its quota.
TEST_F(UploadIntakeTest, AStartIsAnsweredFromWhatTheClientHoldsAndItsQuota) {
  const std::string held = Content(100);
  JobStore(Db()).PutDataset(Sha256Hex(held), "held.clf", held, "alice", 1.0);
  UploadIntake intake(Db(), Spools(), Small(250), Collector());
  intake.Start("c", 1, "upload-1", "held.clf", Sha256Hex(held), held.size(), "alice", 0, 20.0);
  const UploadIntake::Answer present = Next();
  ASSERT_TRUE(present.reply.has_stored()) << present.reply.DebugString();
  EXPECT_TRUE(present.reply.stored().already_present());
  EXPECT_TRUE(present.ended);
  // Another client must send the bytes to hold them.
  intake.Start("c", 2, "upload-2", "held.clf", Sha256Hex(held), std::nullopt, "bob", 0, 20.0);
  const UploadIntake::Answer unknown = Next();
  EXPECT_EQ(unknown.reply.error().code(), proto::ERROR_CODE_UNKNOWN_DATASET);
  EXPECT_TRUE(unknown.ended);
  intake.Start("c", 3, "upload-3", "new.clf", Sha256Hex("x"), 100, "alice", 0, 20.0);
  EXPECT_TRUE(Next().reply.has_upload_started());
  intake.Start("c", 4, "upload-4", "new.clf", Sha256Hex("y"), 100, "alice", 100, 20.0);
  const UploadIntake::Answer over = Next();
  EXPECT_EQ(over.reply.error().code(), proto::ERROR_CODE_QUOTA_EXCEEDED);
  EXPECT_EQ(over.reply.request_id(), 4u);
  EXPECT_EQ(SpoolFiles(), 1u);
}

TEST_F(UploadIntakeTest, ADroppedUploadLosesItsSpoolAndItsChunksAreOfNoUpload) {
  UploadIntake intake(Db(), Spools(), Small(), Collector());
  const std::string content = Content(300);
  Begin(intake, "upload-d", Sha256Hex(content), content.size());
  intake.Append("c", 2, Chunk("upload-d", 0, content.substr(0, 64)));
  Next();
  EXPECT_EQ(SpoolFiles(), 1u);
  intake.Drop("upload-d");
  intake.Append("c", 3, Chunk("upload-d", 64, content.substr(64, 64)));
  EXPECT_EQ(Next().reply.error().code(), proto::ERROR_CODE_UNKNOWN_UPLOAD);
  EXPECT_EQ(SpoolFiles(), 0u);
}

TEST_F(UploadIntakeTest, UnfinishedUploadsLeaveNoSpoolBehind) {
  fs::create_directories(Spools());
  std::ofstream(Spools() / "upload-left-by-a-crash") << "bytes";
  {
    UploadIntake intake(Db(), Spools(), Small(), Collector());
    EXPECT_EQ(SpoolFiles(), 0u) << "what a crash left is still there";
    Begin(intake, "upload-u", Sha256Hex("x"), 1000);
    EXPECT_EQ(SpoolFiles(), 1u);
  }
  EXPECT_FALSE(fs::exists(Spools()));
}

}  // namespace
}  // namespace evoslam
