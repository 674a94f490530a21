#include "common/image/pgm.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class PgmTest : public ::testing::Test {
 protected:
  fs::path Write(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  // The message of the InputError that reading `path` throws.
  std::string ReadError(const fs::path& path, std::size_t* line = nullptr) {
    try {
      ReadPgm(path);
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), path.string());
      if (line != nullptr) *line = e.line();
      return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return "";
  }

  TempDir dir_;
};

TEST_F(PgmTest, WriteReadRoundTrip) {
  GrayImage image;
  image.width = 3;
  image.height = 2;
  image.pixels = {0, 10, 205, 254, 255, 7};
  const fs::path path = dir_ / "a.pgm";
  WritePgm(image, path);
  const GrayImage back = ReadPgm(path);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.maxval, 255);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_EQ(back.at(2, 0), 205);
  EXPECT_EQ(back.at(0, 1), 254);
}

TEST_F(PgmTest, ReadsBinaryWithComments) {
  const std::string header = "P5\n# made by hand\n2 # width\n2\n255\n";
  const fs::path path = Write("c.pgm", header + std::string("\x00\x01\xfe\xff", 4));
  const GrayImage image = ReadPgm(path);
  ASSERT_EQ(image.pixels.size(), 4u);
  EXPECT_EQ(image.at(0, 0), 0);
  EXPECT_EQ(image.at(1, 0), 1);
  EXPECT_EQ(image.at(0, 1), 254);
  EXPECT_EQ(image.at(1, 1), 255);
}

TEST_F(PgmTest, ReadsPlain) {
  const GrayImage image = ReadPgm(Write("p.pgm", "P2\n3 2\n100\n0 50 100\n# mid\n7 8\n9\n"));
  EXPECT_EQ(image.maxval, 100);
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{0, 50, 100, 7, 8, 9}));
}

TEST_F(PgmTest, RejectsBadMagic) {
  EXPECT_THAT(ReadError(Write("m.pgm", "P6\n1 1\n255\nabc")), HasSubstr("P5 or P2"));
  EXPECT_THAT(ReadError(Write("e.pgm", "")), HasSubstr("P5 or P2"));
  EXPECT_THAT(ReadError(Write("m2.pgm", "P55 1 1 255\n")), HasSubstr("magic"));
}

TEST_F(PgmTest, RejectsBadHeaderNumbersWithLine) {
  std::size_t line = 0;
  EXPECT_THAT(ReadError(Write("w.pgm", "P2\n# c\nx 2\n255\n"), &line), HasSubstr("width"));
  EXPECT_EQ(line, 3u);
  EXPECT_THAT(ReadError(Write("h.pgm", "P2\n2\n"), &line), HasSubstr("height"));
  EXPECT_THAT(ReadError(Write("z.pgm", "P2\n0 2\n255\n"), &line), HasSubstr("positive"));
  EXPECT_THAT(ReadError(Write("mv.pgm", "P5\n1 1\n65535\n\x01\x02"), &line),
              HasSubstr("maxval 65535"));
  EXPECT_EQ(line, 3u);
  EXPECT_THAT(ReadError(Write("big.pgm", "P5\n100000 100000\n255\n"), &line), HasSubstr("allowed"));
  EXPECT_THAT(ReadError(Write("huge.pgm", "P5\n99999999999999999999 1\n255\n"), &line),
              HasSubstr("width exceeds"));
}

TEST_F(PgmTest, RejectsTruncatedBinaryData) {
  const std::string message = ReadError(Write("t.pgm", "P5\n3 2\n255\n\x01\x02\x03"));
  EXPECT_THAT(message, HasSubstr("truncated"));
  EXPECT_THAT(message, HasSubstr("expected 3 x 2 = 6 bytes, found 3"));
}

TEST_F(PgmTest, RejectsExtraBinaryData) {
  EXPECT_THAT(ReadError(Write("x.pgm", "P5\n2 1\n255\n\x01\x02\x03\x04")),
              HasSubstr("2 bytes follow"));
}

TEST_F(PgmTest, RejectsBadPlainData) {
  std::size_t line = 0;
  EXPECT_THAT(ReadError(Write("t.pgm", "P2\n2 2\n255\n1 2\n3\n"), &line), HasSubstr("found 3"));
  EXPECT_THAT(ReadError(Write("x.pgm", "P2\n2 1\n255\n1 2 3\n"), &line), HasSubstr("more than"));
  EXPECT_EQ(line, 4u);
  EXPECT_THAT(ReadError(Write("v.pgm", "P2\n2 1\n10\n1\n11\n"), &line),
              HasSubstr("pixel value exceeds 10"));
  EXPECT_EQ(line, 5u);
  EXPECT_THAT(ReadError(Write("n.pgm", "P2\n2 1\n255\n1 -2\n"), &line), HasSubstr("pixel value"));
}

TEST_F(PgmTest, RejectsBinaryValueAboveMaxval) {
  EXPECT_THAT(ReadError(Write("v.pgm", "P5\n2 1\n100\n\x01\xc8")), HasSubstr("exceeds maxval"));
}

TEST_F(PgmTest, AnImageOverTheLimitIsRefusedFromItsHeaderAlone) {
  // 8 GiB of pixels in a sparse file: reading them before the header's size would take minutes
  // and the memory of the machine.
  const fs::path path = Write("huge.pgm", "P5\n65536 131072\n255\n");
  fs::resize_file(path, fs::file_size(path) + (std::uintmax_t{1} << 33));
  try {
    ReadPgm(path, 1'000'000);
    ADD_FAILURE() << "no InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path.string());
    EXPECT_THAT(e.what(), HasSubstr("65536 x 131072 pixels, more than the 1000000 allowed"));
  }
}

TEST_F(PgmTest, AHeaderLongerThanItsFirstBlockIsReadWhole) {
  const std::string comment = "# " + std::string(100'000, 'c') + "\n";
  const GrayImage image = ReadPgm(Write("long.pgm", "P5\n" + comment + "2 1\n255\n\x05\x06"));
  EXPECT_EQ(image.width, 2);
  EXPECT_EQ(image.height, 1);
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{5, 6}));
}

TEST_F(PgmTest, APlainImageLongerThanItsFirstBlockIsReadWhole) {
  std::string values;
  for (int i = 0; i < 40'000; ++i) values += std::to_string(i % 200) + " ";
  const GrayImage image = ReadPgm(Write("plain.pgm", "P2\n200 200\n255\n" + values));
  ASSERT_EQ(image.pixels.size(), 40'000u);
  EXPECT_EQ(image.pixels[39'999], 39'999 % 200);
}

TEST_F(PgmTest, MissingFileNamesPath) {
  EXPECT_THAT(ReadError(dir_ / "none.pgm"), HasSubstr("none.pgm"));
}

TEST_F(PgmTest, WriteRejectsInconsistentImage) {
  GrayImage image;
  image.width = 2;
  image.height = 2;
  image.pixels = {1, 2, 3};
  EXPECT_THROW(WritePgm(image, dir_ / "bad.pgm"), Error);
  image.pixels.push_back(4);
  EXPECT_THROW(WritePgm(image, dir_ / "no_dir" / "a.pgm"), Error);
}

}  // namespace
}  // namespace evoslam
