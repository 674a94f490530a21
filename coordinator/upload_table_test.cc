#include "coordinator/upload_table.h"

#include <gtest/gtest.h>

#include <string>

#include "common/protocol/wire.h"

namespace evoslam {
namespace {

using Clock = UploadTable::Clock;
using std::chrono::seconds;

template <typename Call>
proto::ErrorCode RefusalCode(Call call) {
  try {
    call();
  } catch (const ProtocolError& e) {
    return e.code();
  }
  ADD_FAILURE() << "accepted";
  return proto::ERROR_CODE_UNSPECIFIED;
}

TEST(UploadTableTest, UploadsHaveRandomIdsAndReserveTheirOwnersBytes) {
  UploadTable table(10);
  const Clock::time_point t0;
  const std::string a = table.Begin("alice", "a.clf", 100, t0);
  const std::string b = table.Begin("alice", "b.clf", 50, t0);
  const std::string c = table.Begin("bob", "c.clf", 7, t0);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.rfind("upload-", 0), 0u) << a;
  EXPECT_EQ(table.Reserved("alice"), 150u);
  EXPECT_EQ(table.Reserved("bob"), 7u);
  EXPECT_EQ(table.Reserved("carol"), 0u);
  EXPECT_EQ(table.NameOf(b), "b.clf");
  table.End(a);
  EXPECT_EQ(table.Reserved("alice"), 50u);
  EXPECT_EQ(table.size(), 2u);
  EXPECT_EQ(table.NameOf(a), "");
}

TEST(UploadTableTest, TooManyUploadsAtOnceAreRefused) {
  UploadTable table(2);
  const Clock::time_point t0;
  const std::string a = table.Begin("", "a", 1, t0);
  table.Begin("", "b", 1, t0);
  EXPECT_EQ(RefusalCode([&] { table.Begin("", "c", 1, t0); }), proto::ERROR_CODE_QUEUE_FULL);
  table.End(a);
  EXPECT_NO_THROW(table.Begin("", "c", 1, t0));
}

TEST(UploadTableTest, AChunkOfAnotherOwnersUploadIsAsOfNone) {
  UploadTable table(10);
  const std::string a = table.Begin("alice", "a", 1, Clock::time_point());
  EXPECT_EQ(RefusalCode([&] { table.Accept(a, "bob", Clock::time_point()); }),
            proto::ERROR_CODE_UNKNOWN_UPLOAD);
  EXPECT_EQ(RefusalCode([&] { table.Accept("upload-nonesuch", "alice", Clock::time_point()); }),
            proto::ERROR_CODE_UNKNOWN_UPLOAD);
}

TEST(UploadTableTest, MoreChunksAheadThanTheWindowEndTheUpload) {
  UploadTable table(10);
  const Clock::time_point t0;
  const std::string a = table.Begin("", "a", 1, t0);
  table.Answered(a, t0);  // started
  for (std::uint32_t i = 0; i < kUploadWindow; ++i) table.Accept(a, "", t0);
  EXPECT_EQ(RefusalCode([&] { table.Accept(a, "", t0); }), proto::ERROR_CODE_QUEUE_FULL);
  EXPECT_EQ(table.size(), 0u);
}

TEST(UploadTableTest, AnAnsweredChunkMakesRoomForTheNext) {
  UploadTable table(10);
  const Clock::time_point t0;
  const std::string a = table.Begin("", "a", 1, t0);
  table.Answered(a, t0);
  for (int i = 0; i < 10; ++i) {
    table.Accept(a, "", t0);
    table.Accept(a, "", t0);
    table.Answered(a, t0);
    table.Answered(a, t0);
  }
  EXPECT_EQ(table.size(), 1u);
}

TEST(UploadTableTest, OnlyUploadsSilentWithNothingWaitingAreSilent) {
  UploadTable table(10);
  const Clock::time_point t0;
  const std::string waiting = table.Begin("", "a", 1, t0);  // its start is with the intake
  const std::string idle = table.Begin("", "b", 1, t0);
  table.Answered(idle, t0);
  const std::string recent = table.Begin("", "c", 1, t0);
  table.Answered(recent, t0 + seconds(10));
  EXPECT_EQ(table.Silent(t0 + seconds(5)), std::vector<std::string>{idle});
  table.Accept(idle, "", t0 + seconds(6));
  EXPECT_TRUE(table.Silent(t0 + seconds(5)).empty());
}

TEST(CheckQuotaTest, RefusesOnlyWhatGoesOverAQuota) {
  EXPECT_NO_THROW(CheckQuota("a", 100, 0, 0));
  EXPECT_NO_THROW(CheckQuota("a", 60, 40, 100));
  try {
    CheckQuota("a.clf", 61, 40, 100);
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_QUOTA_EXCEEDED);
    EXPECT_NE(std::string(e.what()).find("over its quota of 100"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace evoslam
