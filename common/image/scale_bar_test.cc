#include "common/image/scale_bar.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/image/bitmap_font.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr Rgb kBarInk{40, 40, 40};

// The longest run of `color` along any row of the image.
int LongestRun(const Image& image, Rgb color) {
  int longest = 0;
  for (int y = 0; y < image.height(); ++y) {
    int run = 0;
    for (int x = 0; x < image.width(); ++x) {
      run = image.at(x, y) == color ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  return longest;
}

TEST(ScaleBarTest, PicksTheLongestRoundLengthThatFits) {
  const ScaleBar two = MakeScaleBar(0.01, 300);
  EXPECT_DOUBLE_EQ(two.metres, 2.0);
  EXPECT_EQ(two.pixels, 200);
  EXPECT_EQ(two.label, "2 m");
  const ScaleBar ten = MakeScaleBar(0.05, 200);
  EXPECT_DOUBLE_EQ(ten.metres, 10.0);
  EXPECT_EQ(ten.pixels, 200);
  EXPECT_EQ(ten.label, "10 m");
  const ScaleBar tenth = MakeScaleBar(0.001, 120);
  EXPECT_NEAR(tenth.metres, 0.1, 1e-12);
  EXPECT_EQ(tenth.pixels, 100);
  EXPECT_EQ(tenth.label, "0.1 m");
  EXPECT_EQ(MakeScaleBar(1.0, 70).label, "50 m");
}

TEST(ScaleBarTest, TheBarTakesBetweenTwoFifthsAndAllOfTheRoomGiven) {
  for (double mpp = 0.003; mpp < 30.0; mpp *= 1.37) {
    const ScaleBar bar = MakeScaleBar(mpp, 250);
    EXPECT_LE(bar.pixels, 250) << mpp;
    EXPECT_GE(bar.pixels, 100) << mpp;
    EXPECT_NEAR(bar.pixels * mpp, bar.metres, mpp) << mpp;
    const double mantissa = bar.metres / std::pow(10.0, std::floor(std::log10(bar.metres) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                std::abs(mantissa - 5) < 1e-9)
        << bar.metres;
  }
}

TEST(ScaleBarTest, BadScalesAreErrors) {
  EXPECT_THROW(MakeScaleBar(0.0, 100), Error);
  EXPECT_THROW(MakeScaleBar(-1.0, 100), Error);
  EXPECT_THROW(MakeScaleBar(std::nan(""), 100), Error);
  EXPECT_THROW(MakeScaleBar(0.01, 0), Error);
}

TEST(ScaleBarTest, DrawsABarOfItsPixelsUnderItsLabel) {
  const ScaleBar bar = MakeScaleBar(0.02, 180);
  const Eigen::Vector2i size = ScaleBarSize(bar, 2);
  Image image(size.x() + 20, size.y() + 20);
  DrawScaleBar(image, 10, 10, bar, kBarInk, 2);
  EXPECT_EQ(LongestRun(image, kBarInk), bar.pixels);
  const auto label = FindText(image, bar.label, kBarInk, 2);
  ASSERT_TRUE(label);
  EXPECT_EQ(label->y(), 10);
  // Everything drawn lies within the size it reports.
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (!(image.at(x, y) == kBarInk)) continue;
      EXPECT_TRUE(x >= 10 && x < 10 + size.x() && y >= 10 && y < 10 + size.y()) << x << "," << y;
    }
  }
  EXPECT_EQ(image.at(10 + (size.x() - bar.pixels) / 2, 10 + size.y() - 1), kBarInk);
}

}  // namespace
}  // namespace evoslam
