#include "common/io/line_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/io/testing_files.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using io_testing::Bzip2Bytes;
using io_testing::GzipBytes;
using io_testing::WriteBytes;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<std::string> ReadAll(LineReader& reader) {
  std::vector<std::string> lines;
  while (const auto line = reader.Next()) lines.emplace_back(*line);
  return lines;
}

std::vector<std::string> ReadAll(const std::filesystem::path& path) {
  LineReader reader(path);
  return ReadAll(reader);
}

// Many numbered lines, long enough to cross the reader's buffer several times.
std::string NumberedLines(int count) {
  std::string text;
  for (int i = 1; i <= count; ++i)
    text += "line " + std::to_string(i) + " " + std::string(40, 'x') + "\n";
  return text;
}

void ExpectNumberedLines(const std::filesystem::path& path, int count) {
  LineReader reader(path);
  int expected = 0;
  while (const auto line = reader.Next()) {
    ++expected;
    ASSERT_EQ(*line, "line " + std::to_string(expected) + " " + std::string(40, 'x'));
    ASSERT_EQ(reader.line_number(), static_cast<std::size_t>(expected));
  }
  EXPECT_EQ(expected, count);
}

template <typename F>
InputError CatchInputError(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", 0, "");
}

TEST(LineReaderTest, SplitsPlainTextIntoLines) {
  TempDir dir;
  WriteBytes(dir / "a.txt", "first\n\nthird\r\nlast without newline");
  LineReader reader(dir / "a.txt");
  EXPECT_EQ(reader.compression(), Compression::kNone);
  EXPECT_EQ(reader.line_number(), 0u);
  EXPECT_THAT(ReadAll(reader), ElementsAre("first", "", "third", "last without newline"));
  EXPECT_EQ(reader.line_number(), 4u);
  EXPECT_FALSE(reader.Next().has_value());
}

TEST(LineReaderTest, EmptyFileHasNoLines) {
  TempDir dir;
  WriteBytes(dir / "empty", "");
  EXPECT_TRUE(ReadAll(dir / "empty").empty());
}

TEST(LineReaderTest, EmptyCompressedFilesHaveNoLines) {
  TempDir dir;
  WriteBytes(dir / "empty.gz", GzipBytes(""));
  WriteBytes(dir / "empty.bz2", Bzip2Bytes(""));
  EXPECT_TRUE(ReadAll(dir / "empty.gz").empty());
  EXPECT_TRUE(ReadAll(dir / "empty.bz2").empty());
}

TEST(LineReaderTest, FinalNewlineDoesNotAddALine) {
  TempDir dir;
  WriteBytes(dir / "a", "a\nb\n");
  EXPECT_THAT(ReadAll(dir / "a"), ElementsAre("a", "b"));
}

TEST(LineReaderTest, CountsLinesAcrossBufferRefills) {
  TempDir dir;
  WriteBytes(dir / "many.txt", NumberedLines(100000));
  ExpectNumberedLines(dir / "many.txt", 100000);
}

TEST(LineReaderTest, ReadsLinesLongerThanItsBuffer) {
  TempDir dir;
  const std::string long_line(3'000'000, 'q');
  WriteBytes(dir / "long", "short\n" + long_line + "\nend\n");
  EXPECT_THAT(ReadAll(dir / "long"), ElementsAre("short", long_line, "end"));
}

TEST(LineReaderTest, DecompressesGzipWhateverTheName) {
  TempDir dir;
  WriteBytes(dir / "log.txt", GzipBytes(NumberedLines(50000)));
  EXPECT_EQ(LineReader(dir / "log.txt").compression(), Compression::kGzip);
  ExpectNumberedLines(dir / "log.txt", 50000);
}

TEST(LineReaderTest, DecompressesBzip2WhateverTheName) {
  TempDir dir;
  WriteBytes(dir / "log.gz", Bzip2Bytes(NumberedLines(50000)));
  EXPECT_EQ(LineReader(dir / "log.gz").compression(), Compression::kBzip2);
  ExpectNumberedLines(dir / "log.gz", 50000);
}

TEST(LineReaderTest, ReadsConcatenatedGzipMembers) {
  TempDir dir;
  WriteBytes(dir / "two.gz", GzipBytes("a\nb") + GzipBytes("c\nd\n"));
  EXPECT_THAT(ReadAll(dir / "two.gz"), ElementsAre("a", "bc", "d"));
}

TEST(LineReaderTest, ReadsConcatenatedBzip2Streams) {
  TempDir dir;
  WriteBytes(dir / "two.bz2", Bzip2Bytes("a\nb\n") + Bzip2Bytes("c\nd\n") + Bzip2Bytes("e\n"));
  EXPECT_THAT(ReadAll(dir / "two.bz2"), ElementsAre("a", "b", "c", "d", "e"));
}

TEST(LineReaderTest, MissingFileNamesTheFile) {
  TempDir dir;
  const auto path = dir / "no_such_log.clf";
  const InputError e = CatchInputError([&] { LineReader reader(path); });
  EXPECT_EQ(e.source(), path.string());
  EXPECT_THAT(e.what(), HasSubstr("no_such_log.clf"));
  EXPECT_THAT(e.what(), HasSubstr("cannot open"));
}

TEST(LineReaderTest, DirectoryIsAnInputError) {
  TempDir dir;
  const InputError e = CatchInputError([&] {
    LineReader reader(dir.path());
    ReadAll(reader);
  });
  EXPECT_EQ(e.source(), dir.path().string());
}

TEST(LineReaderTest, RejectsXzAndZstdAsUnsupported) {
  TempDir dir;
  WriteBytes(dir / "log.xz", std::string("\xFD"
                                         "7zXZ\0rest",
                                         10));
  WriteBytes(dir / "log.zst", std::string("\x28\xB5\x2F\xFD"
                                          "rest"));
  for (const char* name : {"log.xz", "log.zst"}) {
    const InputError e = CatchInputError([&] { LineReader reader(dir / name); });
    EXPECT_THAT(e.what(), HasSubstr(name));
    EXPECT_THAT(e.what(), HasSubstr("unsupported compression"));
  }
  EXPECT_THAT(CatchInputError([&] { LineReader reader(dir / "log.xz"); }).what(), HasSubstr("xz"));
  EXPECT_THAT(CatchInputError([&] { LineReader reader(dir / "log.zst"); }).what(),
              HasSubstr("zstd"));
}

TEST(LineReaderTest, TruncatedGzipIsAnErrorAtTheLineReached) {
  TempDir dir;
  const std::string text = NumberedLines(20000);
  const std::string gz = GzipBytes(text);
  WriteBytes(dir / "cut.gz", gz.substr(0, gz.size() / 2));
  LineReader reader(dir / "cut.gz");
  const InputError e = CatchInputError([&] { ReadAll(reader); });
  EXPECT_EQ(e.source(), (dir / "cut.gz").string());
  EXPECT_THAT(e.what(), HasSubstr("truncated gzip"));
  // Half the compressed bytes give some but not all lines; the error is at the next one.
  EXPECT_GT(e.line(), 1u);
  EXPECT_LT(e.line(), 20000u);
  EXPECT_EQ(e.line(), reader.line_number() + 1);
}

TEST(LineReaderTest, TruncatedBzip2IsAnError) {
  TempDir dir;
  const std::string bz = Bzip2Bytes(NumberedLines(20000));
  WriteBytes(dir / "cut.bz2", bz.substr(0, bz.size() - 100));
  LineReader reader(dir / "cut.bz2");
  const InputError e = CatchInputError([&] { ReadAll(reader); });
  EXPECT_THAT(e.what(), HasSubstr("cut.bz2"));
  EXPECT_THAT(e.what(), HasSubstr("truncated bzip2"));
  EXPECT_EQ(e.line(), reader.line_number() + 1);
}

TEST(LineReaderTest, CorruptBzip2IsAnError) {
  TempDir dir;
  std::string bz = Bzip2Bytes(NumberedLines(20000));
  for (std::size_t i = bz.size() / 2; i < bz.size() / 2 + 64; ++i)
    bz[i] = static_cast<char>(~bz[i]);
  WriteBytes(dir / "bad.bz2", bz);
  const InputError e = CatchInputError([&] { ReadAll(dir / "bad.bz2"); });
  EXPECT_THAT(e.what(), HasSubstr("bad.bz2"));
  EXPECT_THAT(e.what(), HasSubstr("corrupt bzip2"));
}

TEST(LineReaderTest, CorruptGzipIsAnError) {
  TempDir dir;
  std::string gz = GzipBytes(NumberedLines(20000));
  for (std::size_t i = gz.size() / 2; i < gz.size() / 2 + 64; ++i)
    gz[i] = static_cast<char>(~gz[i]);
  WriteBytes(dir / "bad.gz", gz);
  const InputError e = CatchInputError([&] { ReadAll(dir / "bad.gz"); });
  EXPECT_THAT(e.what(), HasSubstr("bad.gz"));
  EXPECT_THAT(e.what(), HasSubstr("gzip"));
}

TEST(LineReaderTest, MovedReaderContinuesWhereItWas) {
  TempDir dir;
  WriteBytes(dir / "a", "1\n2\n3\n");
  LineReader first(dir / "a");
  ASSERT_EQ(first.Next(), "1");
  LineReader second(std::move(first));
  EXPECT_EQ(second.Next(), "2");
  EXPECT_EQ(second.line_number(), 2u);
}

}  // namespace
}  // namespace evoslam
