#include "common/io/file_bytes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/util/error.h"
#include "common/util/scratch_dir.h"

namespace evoslam {
namespace {

TEST(FileBytesTest, ReadsEveryByteAndNamesAFileItCannotRead) {
  testing::ScratchDir dir;
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

}  // namespace
}  // namespace evoslam
