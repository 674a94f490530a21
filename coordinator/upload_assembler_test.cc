#include "coordinator/upload_assembler.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/protocol/wire.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

// Bytes of every value, so that a byte lost or moved shows in the hash.
std::string Pattern(std::size_t size) {
  std::string bytes(size, '\0');
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>((i * 131 + 17) % 256);
  return bytes;
}

class UploadAssemblerTest : public ::testing::Test {
 protected:
  std::filesystem::path Spool() const { return dir_ / "upload-1"; }
  UploadAssembler Make(const std::string& content, std::size_t max_chunk = 100) {
    return UploadAssembler(Spool(), "upload-1", "log.clf", Sha256Hex(content), content.size(),
                           max_chunk);
  }
  // The code of the refusal `append` throws; fails the test when it throws none.
  template <typename Append>
  static proto::ErrorCode Refusal(Append append) {
    try {
      append();
    } catch (const ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find("log.clf"), std::string::npos) << e.what();
      return e.code();
    }
    ADD_FAILURE() << "accepted";
    return proto::ERROR_CODE_UNSPECIFIED;
  }
  TempDir dir_;
};

TEST_F(UploadAssemblerTest, ChunksInOrderAreReadBackAsTheDataset) {
  const std::string content = Pattern(250);
  UploadAssembler upload = Make(content);
  EXPECT_FALSE(upload.Append(0, std::string_view(content).substr(0, 100)));
  EXPECT_FALSE(upload.Append(100, std::string_view(content).substr(100, 100)));
  EXPECT_EQ(upload.received(), 200u);
  EXPECT_FALSE(upload.complete());
  EXPECT_TRUE(upload.Append(200, std::string_view(content).substr(200)));
  EXPECT_TRUE(upload.complete());
  // Read back in pieces of another size than the chunks'.
  std::string back;
  for (std::size_t at = 0; at < content.size(); at += 64) {
    std::string piece(std::min<std::size_t>(64, content.size() - at), '\0');
    upload.ReadBack(piece);
    back += piece;
  }
  EXPECT_EQ(back, content);
  std::string more(1, '\0');
  EXPECT_THROW(upload.ReadBack(more), Error) << "read past the end";
}

TEST_F(UploadAssemblerTest, TheSpoolFileGoesWithTheUpload) {
  {
    UploadAssembler upload = Make(Pattern(10));
    upload.Append(0, Pattern(5));
    EXPECT_TRUE(std::filesystem::exists(Spool()));
  }
  EXPECT_FALSE(std::filesystem::exists(Spool()));
}

TEST_F(UploadAssemblerTest, AnEmptyDatasetIsOneEmptyChunk) {
  UploadAssembler upload = Make("");
  EXPECT_TRUE(upload.Append(0, ""));
  EXPECT_EQ(Refusal([&] { upload.Append(0, ""); }), proto::ERROR_CODE_INVALID) << "after the last";
}

TEST_F(UploadAssemblerTest, AChunkOutOfOrderIsRefusedAndSpoilsTheUpload) {
  const std::string content = Pattern(300);
  UploadAssembler upload = Make(content);
  upload.Append(0, content.substr(0, 100));
  EXPECT_EQ(Refusal([&] { upload.Append(200, content.substr(200, 100)); }),
            proto::ERROR_CODE_INVALID);
  // Even the right chunk now: the client must start again.
  EXPECT_EQ(Refusal([&] { upload.Append(100, content.substr(100, 100)); }),
            proto::ERROR_CODE_INVALID);
  EXPECT_FALSE(upload.complete());
}

TEST_F(UploadAssemblerTest, AChunkRepeatedIsRefused) {
  const std::string content = Pattern(300);
  UploadAssembler upload = Make(content);
  upload.Append(0, content.substr(0, 100));
  EXPECT_EQ(Refusal([&] { upload.Append(0, content.substr(0, 100)); }), proto::ERROR_CODE_INVALID);
}

TEST_F(UploadAssemblerTest, BytesPastTheAnnouncedSizeAreRefused) {
  const std::string content = Pattern(150);
  UploadAssembler upload = Make(content);
  upload.Append(0, content.substr(0, 100));
  EXPECT_EQ(Refusal([&] { upload.Append(100, Pattern(60)); }), proto::ERROR_CODE_INVALID);
}

TEST_F(UploadAssemblerTest, AChunkOverTheLimitIsTooLarge) {
  const std::string content = Pattern(300);
  UploadAssembler upload = Make(content, 100);
  try {
    upload.Append(0, content.substr(0, 101));
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_TOO_LARGE) << e.what();
  }
  EXPECT_EQ(Refusal([&] { upload.Append(0, content.substr(0, 100)); }), proto::ERROR_CODE_INVALID);
}

TEST_F(UploadAssemblerTest, AnEmptyChunkOfADatasetIsRefused) {
  UploadAssembler upload = Make(Pattern(10));
  EXPECT_EQ(Refusal([&] { upload.Append(0, ""); }), proto::ERROR_CODE_INVALID);
}

TEST_F(UploadAssemblerTest, BytesThatHashToAnotherShaAreRefusedAtTheEnd) {
  const std::string content = Pattern(150);
  UploadAssembler upload(Spool(), "upload-1", "log.clf", Sha256Hex("other bytes"), content.size(),
                         100);
  EXPECT_FALSE(upload.Append(0, content.substr(0, 100)));
  try {
    upload.Append(100, content.substr(100));
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_INVALID);
    EXPECT_NE(std::string(e.what()).find(Sha256Hex(content)), std::string::npos) << e.what();
  }
  EXPECT_FALSE(upload.complete());
  std::string piece(1, '\0');
  EXPECT_THROW(upload.ReadBack(piece), Error);
}

TEST_F(UploadAssemblerTest, ASpoolThatCannotBeCreatedIsAnErrorNamingIt) {
  try {
    UploadAssembler upload(dir_ / "missing" / "upload-1", "upload-1", "log.clf", Sha256Hex(""), 0,
                           100);
    FAIL() << "created";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace evoslam
