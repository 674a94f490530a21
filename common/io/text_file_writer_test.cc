#include "common/io/text_file_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/io/testing_files.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using io_testing::ReadBytes;
using ::testing::HasSubstr;

TEST(TextFileWriterTest, WritesWhatItIsGiven) {
  TempDir dir;
  TextFileWriter writer(dir / "a.txt");
  writer.Write("one\n");
  writer.Write("two");
  writer.Close();
  EXPECT_EQ(ReadBytes(dir / "a.txt"), "one\ntwo");
  EXPECT_THROW(writer.Write("late"), Error);
}

TEST(TextFileWriterTest, CannotCreateIsAnErrorNamingThePath) {
  TempDir dir;
  const auto path = dir / "missing" / "a.txt";
  try {
    TextFileWriter writer(path);
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
}

TEST(TextFileWriterTest, FullDiskIsReported) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const auto fail = [] {
    TextFileWriter writer("/dev/full");
    writer.Write(std::string(1 << 16, 'x'));
    writer.Close();
  };
  EXPECT_THROW(fail(), Error);
}

}  // namespace
}  // namespace evoslam
