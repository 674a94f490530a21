#include "common/image/image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr Rgb kRed{255, 0, 0};

std::set<std::pair<int, int>> PixelsOf(const Image& image, Rgb color) {
  std::set<std::pair<int, int>> out;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (image.at(x, y) == color) out.insert({x, y});
    }
  }
  return out;
}

TEST(ImageTest, ConstructsFilled) {
  const Image image(4, 3, {1, 2, 3});
  EXPECT_EQ(image.width(), 4);
  EXPECT_EQ(image.height(), 3);
  EXPECT_EQ(PixelsOf(image, {1, 2, 3}).size(), 12u);
  EXPECT_THROW(Image(-1, 3), Error);
}

TEST(ImageTest, SetPixelIgnoresOutside) {
  Image image(3, 2);
  image.SetPixel(2, 1, kRed);
  image.SetPixel(-1, 0, kRed);
  image.SetPixel(3, 0, kRed);
  image.SetPixel(0, 2, kRed);
  EXPECT_EQ(PixelsOf(image, kRed), (std::set<std::pair<int, int>>{{2, 1}}));
}

TEST(ImageTest, HorizontalLineCoversItsPixels) {
  Image image(10, 5);
  image.DrawLine(1, 2, 6, 2, kRed);
  std::set<std::pair<int, int>> expected;
  for (int x = 1; x <= 6; ++x) expected.insert({x, 2});
  EXPECT_EQ(PixelsOf(image, kRed), expected);
}

TEST(ImageTest, DiagonalLineIsEightConnected) {
  Image image(10, 10);
  image.DrawLine(0, 0, 9, 9, kRed);
  std::set<std::pair<int, int>> expected;
  for (int i = 0; i < 10; ++i) expected.insert({i, i});
  EXPECT_EQ(PixelsOf(image, kRed), expected);
}

TEST(ImageTest, ShallowLineHasOnePixelPerColumn) {
  Image image(20, 10);
  image.DrawLine(0, 1, 19, 7, kRed);
  const auto pixels = PixelsOf(image, kRed);
  EXPECT_EQ(pixels.size(), 20u);
  for (const auto& [x, y] : pixels) {
    const double ideal = 1.0 + 6.0 * x / 19.0;
    EXPECT_LE(std::abs(y - ideal), 0.5 + 1e-9) << x;
  }
}

TEST(ImageTest, ThickLineUsesSquareBrush) {
  Image image(10, 10);
  image.DrawLine(3, 4, 3, 4, kRed, 3);
  std::set<std::pair<int, int>> expected;
  for (int y = 3; y <= 5; ++y) {
    for (int x = 2; x <= 4; ++x) expected.insert({x, y});
  }
  EXPECT_EQ(PixelsOf(image, kRed), expected);

  Image even(10, 10);
  even.DrawLine(1, 1, 5, 1, kRed, 2);
  EXPECT_EQ(PixelsOf(even, kRed).size(), 12u);  // rows 1 and 2, columns 1..6
  EXPECT_EQ(even.at(6, 2), kRed);
  EXPECT_EQ(even.at(1, 0), kWhite);
}

// Reference: stamp the square brush at every rounded major-axis step.
Image StampedLine(int w, int h, double x0, double y0, double x1, double y1, int thickness) {
  Image image(w, h);
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const double a0 = x_major ? x0 : y0;
  const double a1 = x_major ? x1 : y1;
  const double b0 = x_major ? y0 : x0;
  const double slope = a1 == a0 ? 0.0 : ((x_major ? y1 : x1) - b0) / (a1 - a0);
  const int lo = -(thickness - 1) / 2;
  const int hi = thickness / 2;
  const int first = static_cast<int>(std::lround(std::min(a0, a1)));
  const int last = static_cast<int>(std::lround(std::max(a0, a1)));
  for (int a = first; a <= last; ++a) {
    const int b = static_cast<int>(std::lround(b0 + (a - a0) * slope));
    for (int i = lo; i <= hi; ++i) {
      for (int j = lo; j <= hi; ++j) {
        if (x_major) {
          image.SetPixel(a + i, b + j, kRed);
        } else {
          image.SetPixel(b + j, a + i, kRed);
        }
      }
    }
  }
  return image;
}

TEST(ImageTest, ThickLinesEqualBrushStamps) {
  const double lines[][4] = {{2.2, 3.1, 17.6, 9.4}, {5, 18, 7.3, 1.2},    {-3, -4, 12.5, 25},
                             {19, 2, 1, 3.9},       {4.4, 4.6, 4.4, 4.6}, {10, 0, 10, 19}};
  for (const auto& l : lines) {
    for (int thickness = 1; thickness <= 6; ++thickness) {
      Image image(20, 20);
      image.DrawLine(l[0], l[1], l[2], l[3], kRed, thickness);
      EXPECT_EQ(PixelsOf(image, kRed),
                PixelsOf(StampedLine(20, 20, l[0], l[1], l[2], l[3], thickness), kRed))
          << l[0] << " " << l[1] << " " << l[2] << " " << l[3] << " t=" << thickness;
    }
  }
}

TEST(ImageTest, HugeThicknessFillsQuickly) {
  Image image(50, 40);
  image.DrawLine(10, 10, 30, 20, kRed, 1 << 30);
  EXPECT_EQ(PixelsOf(image, kRed).size(), 50u * 40u);
}

TEST(ImageTest, ZeroThicknessDrawsNothing) {
  Image image(5, 5);
  image.DrawLine(0, 0, 4, 4, kRed, 0);
  EXPECT_TRUE(PixelsOf(image, kRed).empty());
}

TEST(ImageTest, LineClipsToImage) {
  Image image(10, 10);
  image.DrawLine(-5, 5, 15, 5, kRed);
  std::set<std::pair<int, int>> expected;
  for (int x = 0; x < 10; ++x) expected.insert({x, 5});
  EXPECT_EQ(PixelsOf(image, kRed), expected);
}

TEST(ImageTest, HugeAndNonFiniteLinesAreSafe) {
  Image image(8, 8);
  image.DrawLine(-1e300, 3, 1e300, 3, kRed);
  EXPECT_EQ(PixelsOf(image, kRed).size(), 8u);
  image.DrawLine(std::numeric_limits<double>::quiet_NaN(), 0, 5, 5, {0, 0, 1});
  image.DrawLine(0, 0, std::numeric_limits<double>::infinity(), 5, {0, 0, 1});
  EXPECT_TRUE(PixelsOf(image, {0, 0, 1}).empty());
  image.DrawLine(-100, -100, -50, -60, {0, 0, 1}, 5);
  EXPECT_TRUE(PixelsOf(image, {0, 0, 1}).empty());
}

TEST(ImageTest, ThickLineJustOutsideStillReachesEdge) {
  Image image(10, 10);
  image.DrawLine(-1, 0, -1, 9, kRed, 3);  // brush reaches one pixel to the right
  std::set<std::pair<int, int>> expected;
  for (int y = 0; y < 10; ++y) expected.insert({0, y});
  EXPECT_EQ(PixelsOf(image, kRed), expected);
}

TEST(ImageTest, DiscFillsPixelsWithinRadius) {
  Image image(20, 20);
  image.DrawDisc(10, 10, 3, kRed);
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool inside = (x - 10) * (x - 10) + (y - 10) * (y - 10) <= 9;
      EXPECT_EQ(image.at(x, y) == kRed, inside) << x << "," << y;
    }
  }
}

TEST(ImageTest, DiscClipsAndRejectsBadInput) {
  Image image(5, 5);
  image.DrawDisc(0, 0, 2, kRed);
  const auto pixels = PixelsOf(image, kRed);
  EXPECT_EQ(pixels,
            (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {0, 2}}));
  image.DrawDisc(std::numeric_limits<double>::quiet_NaN(), 1, 3, {0, 0, 1});
  image.DrawDisc(2, 2, -1, {0, 0, 1});
  image.DrawDisc(1e300, 1e300, 1e300, {0, 0, 1});
  EXPECT_TRUE(PixelsOf(image, {0, 0, 1}).empty());
}

TEST(ImageTest, BlendGoesFromOneColourToTheOther) {
  const Rgb blue{40, 90, 230};
  EXPECT_EQ(Blend(blue, kWhite, 0.0), blue);
  EXPECT_EQ(Blend(blue, kWhite, 1.0), kWhite);
  EXPECT_EQ(Blend(blue, kWhite, 0.5), (Rgb{148, 173, 243}));
  EXPECT_EQ(Blend(blue, kWhite, -3.0), blue);
  EXPECT_EQ(Blend(blue, kWhite, 7.0), kWhite);
}

TEST(ImageTest, FillRectClipsToTheImage) {
  Image image(6, 5);
  image.FillRect(4, 3, 10, 10, kRed);
  EXPECT_EQ(PixelsOf(image, kRed), (std::set<std::pair<int, int>>{{4, 3}, {5, 3}, {4, 4}, {5, 4}}));
  image.FillRect(-5, -5, 6, 6, {0, 0, 1});
  EXPECT_EQ(PixelsOf(image, {0, 0, 1}), (std::set<std::pair<int, int>>{{0, 0}}));
  image.FillRect(2, 2, 0, 3, {0, 0, 2});
  image.FillRect(1 << 30, 0, 1 << 30, 1, {0, 0, 2});
  EXPECT_TRUE(PixelsOf(image, {0, 0, 2}).empty());
}

TEST(ImageTest, PasteCopiesWhatFallsWithinTheImage) {
  Image stamp(3, 2, kRed);
  stamp.at(0, 0) = {0, 0, 1};
  Image image(5, 4);
  image.Paste(stamp, 3, 2);
  EXPECT_EQ(image.at(3, 2), (Rgb{0, 0, 1}));
  EXPECT_EQ(PixelsOf(image, kRed), (std::set<std::pair<int, int>>{{4, 2}, {3, 3}, {4, 3}}));
  image.Paste(stamp, -2, -1);
  EXPECT_EQ(image.at(0, 0), kRed);
  image.Paste(stamp, 1 << 30, -(1 << 30));
}

}  // namespace
}  // namespace evoslam
