#include "common/io/file_bytes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

TEST(FileBytesTest, ReadsEveryByteAndNamesAFileItCannotRead) {
  TempDir dir;
  const std::string bytes("a\0b\r\nc", 6);
  std::ofstream(dir / "f", std::ios::binary) << bytes;
  EXPECT_EQ(ReadFileBytes(dir / "f"), bytes);
  try {
    ReadFileBytes(dir / "missing.clf");
    FAIL() << "a missing file must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.clf"), std::string::npos) << e.what();
  }
  std::filesystem::create_directory(dir / "logs.clf");
  try {
    ReadFileBytes(dir / "logs.clf");
    FAIL() << "a directory must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("logs.clf: is a directory"), std::string::npos)
        << e.what();
  }
}

TEST(FileBytesTest, WritesEveryByteAndNamesAFileItCannotWrite) {
  TempDir dir;
  const std::string bytes("a\0b\r\nc", 6);
  WriteFileBytes(dir / "f", "an older, longer content");
  WriteFileBytes(dir / "f", bytes);
  EXPECT_EQ(ReadFileBytes(dir / "f"), bytes);
  try {
    WriteFileBytes(dir / "no" / "such" / "dir.txt", bytes);
    FAIL() << "a file in a missing directory cannot be written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("dir.txt"), std::string::npos) << e.what();
  }
  if (!std::filesystem::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full to stand for a full disk";
  // The bytes fit the stream's buffer, so the disk's refusal comes only at the close.
  EXPECT_THROW(WriteFileBytes("/dev/full", bytes), Error);
}

}  // namespace
}  // namespace evoslam
