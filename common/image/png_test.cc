#include <png.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

#include "common/image/image.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;

class PngTest : public ::testing::Test {
 protected:
  // Writes raw pixel bytes of the given libpng format, to test reading non-RGB PNGs.
  void WriteRaw(const fs::path& path, int width, int height, png_uint_32 format,
                const std::vector<std::uint8_t>& bytes) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = width;
    png.height = height;
    png.format = format;
    ASSERT_NE(png_image_write_to_file(&png, path.c_str(), 0, bytes.data(), 0, nullptr), 0)
        << png.message;
  }

  TempDir dir_;
};

TEST_F(PngTest, RoundTripsEveryPixel) {
  Image image(7, 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      image.at(x, y) = {static_cast<std::uint8_t>(x * 30), static_cast<std::uint8_t>(y * 50),
                        static_cast<std::uint8_t>((x * 7 + y * 13) % 256)};
    }
  }
  const fs::path path = dir_ / "a.png";
  WritePng(image, path);
  const Image back = ReadPng(path);
  ASSERT_EQ(back.width(), 7);
  ASSERT_EQ(back.height(), 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) EXPECT_EQ(back.at(x, y), image.at(x, y)) << x << "," << y;
  }
}

// The colour type in the PNG's header: 2 for RGB, 3 for a palette.
int ColorType(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(25);  // signature 8, chunk length 4, "IHDR" 4, width 4, height 4, bit depth 1
  return in.get();
}

TEST_F(PngTest, FewColoursAreWrittenWithAPaletteAndManyAsRgb) {
  Image few(300, 200, {205, 205, 205});
  few.DrawLine(0, 0, 299, 199, {220, 30, 30}, 3);
  few.FillRect(10, 150, 40, 20, {0, 0, 0});
  Image many(300, 200);
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 300; ++x) {
      many.at(x, y) = {static_cast<std::uint8_t>(x % 256), static_cast<std::uint8_t>(y),
                       static_cast<std::uint8_t>(x / 256)};
    }
  }
  for (const auto& [name, image, type] :
       {std::tuple{"few.png", few, 3}, std::tuple{"many.png", many, 2}}) {
    const fs::path path = dir_ / name;
    WritePng(image, path);
    EXPECT_EQ(ColorType(path), type) << name;
    const Image back = ReadPng(path);
    ASSERT_EQ(back.width(), image.width());
    ASSERT_EQ(back.height(), image.height());
    int differ = 0;
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) differ += !(back.at(x, y) == image.at(x, y));
    }
    EXPECT_EQ(differ, 0) << name;
  }
  // The same picture, the same bytes.
  WritePng(few, dir_ / "again.png");
  std::ifstream a(dir_ / "few.png", std::ios::binary), b(dir_ / "again.png", std::ios::binary);
  EXPECT_TRUE(
      std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b), {}));
}

TEST_F(PngTest, ReadsGrayAsEqualChannels) {
  const fs::path path = dir_ / "gray.png";
  WriteRaw(path, 3, 2, PNG_FORMAT_GRAY, {0, 100, 205, 254, 255, 17});
  const Image image = ReadPng(path);
  ASSERT_EQ(image.width(), 3);
  ASSERT_EQ(image.height(), 2);
  EXPECT_EQ(image.at(1, 0), (Rgb{100, 100, 100}));
  EXPECT_EQ(image.at(2, 0), (Rgb{205, 205, 205}));
  EXPECT_EQ(image.at(0, 1), (Rgb{254, 254, 254}));
  EXPECT_EQ(image.at(2, 1), (Rgb{17, 17, 17}));
}

TEST_F(PngTest, ReadsRgbaCompositedOnWhite) {
  const fs::path path = dir_ / "rgba.png";
  WriteRaw(path, 2, 1, PNG_FORMAT_RGBA, {10, 20, 30, 255, 10, 20, 30, 0});
  const Image image = ReadPng(path);
  EXPECT_EQ(image.at(0, 0), (Rgb{10, 20, 30}));
  EXPECT_EQ(image.at(1, 0), (Rgb{255, 255, 255}));
}

TEST_F(PngTest, MissingFileNamesPath) {
  const fs::path path = dir_ / "missing.png";
  try {
    ReadPng(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path.string());
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos);
  }
}

TEST_F(PngTest, NotAPngIsInputError) {
  const fs::path path = dir_ / "text.png";
  std::ofstream(path) << "this is not a png\n";
  EXPECT_THROW(ReadPng(path), InputError);
}

TEST_F(PngTest, TruncatedPngIsInputError) {
  Image image(64, 64, {1, 2, 3});
  for (int i = 0; i < 64; ++i) image.at(i, i) = {200, 100, 50};
  const fs::path path = dir_ / "full.png";
  WritePng(image, path);
  const auto size = fs::file_size(path);
  fs::resize_file(path, size / 2);
  EXPECT_THROW(ReadPng(path), InputError);
}

TEST_F(PngTest, WriteFailureNamesPath) {
  const fs::path path = dir_ / "no_such_dir" / "out.png";
  try {
    WritePng(Image(2, 2), path);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos);
  }
  EXPECT_THROW(WritePng(Image(0, 3), dir_ / "empty.png"), Error);
}

}  // namespace
}  // namespace evoslam
