#include "common/image/bitmap_font.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace evoslam {
namespace {

constexpr Rgb kFontInk{10, 20, 30};

std::set<std::pair<int, int>> InkOf(const Image& image) {
  std::set<std::pair<int, int>> out;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (image.at(x, y) == kFontInk) out.insert({x, y});
    }
  }
  return out;
}

std::set<std::pair<int, int>> Glyph(char c) {
  Image image(kGlyphWidth, kGlyphHeight);
  DrawText(image, 0, 0, std::string(1, c), kFontInk);
  return InkOf(image);
}

TEST(BitmapFontTest, EveryPrintableGlyphIsInkedAndUnlikeTheOthers) {
  std::set<std::set<std::pair<int, int>>> seen;
  for (char c = ' '; c <= '~'; ++c) {
    const auto glyph = Glyph(c);
    if (c == ' ') {
      EXPECT_TRUE(glyph.empty());
    } else {
      EXPECT_GE(glyph.size(), 2u) << c;
    }
    EXPECT_TRUE(seen.insert(glyph).second) << "'" << c << "' looks like another glyph";
  }
  EXPECT_EQ(seen.size(), 95u);
}

TEST(BitmapFontTest, CapitalsStandOnTheBaselineAndDescendersGoBelow) {
  for (const char c : std::string("AEHLMTZ0123456789")) {
    int bottom = 0;
    for (const auto& [x, y] : Glyph(c)) bottom = std::max(bottom, y);
    EXPECT_EQ(bottom, 6) << c;
  }
  for (const char c : std::string("gjpqy")) {
    int bottom = 0;
    for (const auto& [x, y] : Glyph(c)) bottom = std::max(bottom, y);
    EXPECT_EQ(bottom, 8) << c;
  }
}

TEST(BitmapFontTest, DrawsAGlyphWhereToldAndScaled) {
  Image image(20, 30);
  DrawText(image, 2, 3, "L", kFontInk);
  std::set<std::pair<int, int>> expected;
  for (int y = 3; y <= 9; ++y) expected.insert({2, y});
  for (int x = 2; x <= 6; ++x) expected.insert({x, 9});
  EXPECT_EQ(InkOf(image), expected);

  Image big(20, 30);
  DrawText(big, 0, 0, "L", kFontInk, 3);
  EXPECT_EQ(InkOf(big).size(), 9 * expected.size());
  EXPECT_EQ(big.at(0, 0), kFontInk);
  EXPECT_EQ(big.at(2, 2), kFontInk);
  EXPECT_EQ(big.at(14, 20), kFontInk) << "the bottom row's last block";
  EXPECT_EQ(big.at(15, 20), kWhite);
}

TEST(BitmapFontTest, TextWidthSpansTheGlyphsWithoutTheLastGap) {
  EXPECT_EQ(TextWidth(""), 0);
  EXPECT_EQ(TextWidth("a"), 5);
  EXPECT_EQ(TextWidth("ab"), 11);
  EXPECT_EQ(TextWidth("ab", 2), 22);
  EXPECT_EQ(TextHeight(2), 18);
  Image image(40, 12);
  DrawText(image, 0, 0, "HH", kFontInk);
  int right = 0;
  for (const auto& [x, y] : InkOf(image)) right = std::max(right, x);
  EXPECT_EQ(right + 1, TextWidth("HH"));
}

TEST(BitmapFontTest, OtherBytesDrawAsAQuestionMark) {
  for (const char c : {'\x01', '\n', '\x7f', static_cast<char>(0xE9)}) {
    EXPECT_EQ(Glyph(c), Glyph('?')) << static_cast<int>(c);
  }
}

TEST(BitmapFontTest, TextPastTheEdgesIsClipped) {
  Image image(8, 8);
  DrawText(image, -3, -4, "MW", kFontInk, 2);
  DrawText(image, 6, 6, "MW", kFontInk, 2);
  EXPECT_FALSE(InkOf(image).empty());
  DrawText(image, 1 << 30, 1 << 30, "far", kFontInk, 4);
}

TEST(BitmapFontTest, WrapTextBreaksAtSpacesWithinTheWidth) {
  const int nine = TextWidth("123456789");
  EXPECT_EQ(WrapText("the quick brown fox", nine),
            (std::vector<std::string>{"the quick", "brown fox"}));
  EXPECT_EQ(WrapText("the quick brown fox", 1000),
            (std::vector<std::string>{"the quick brown fox"}));
  EXPECT_EQ(WrapText("a  b", 1000), (std::vector<std::string>{"a b"}));
  EXPECT_EQ(WrapText("", 100), (std::vector<std::string>{""}));
  // A word wider than a line is cut between glyphs.
  EXPECT_EQ(WrapText("ab abcdefghijk", TextWidth("abcd", 2), 2),
            (std::vector<std::string>{"ab", "abcd", "efgh", "ijk"}));
  for (const std::string& line : WrapText("pictures that explain themselves, in words", 60)) {
    EXPECT_LE(TextWidth(line), 60) << line;
  }
}

TEST(BitmapFontTest, FindTextFindsWhatWasDrawnAndNothingElse) {
  Image image(200, 60);
  DrawText(image, 17, 23, "1.40 cm", kFontInk, 2);
  DrawText(image, 5, 2, "other", kFontInk);
  const auto at = FindText(image, "1.40 cm", kFontInk, 2);
  ASSERT_TRUE(at);
  EXPECT_EQ(*at, Eigen::Vector2i(17, 23));
  EXPECT_EQ(FindText(image, "other", kFontInk), Eigen::Vector2i(5, 2));
  EXPECT_FALSE(FindText(image, "1.40 cm", kFontInk, 1)) << "another scale";
  EXPECT_FALSE(FindText(image, "1.41 cm", kFontInk, 2));
  EXPECT_FALSE(FindText(image, "1.40 cm", {0, 0, 0}, 2)) << "another colour";
  EXPECT_FALSE(FindText(image, "1.40 cm wide", kFontInk, 2)) << "more than was drawn";
  image.FillRect(21, 23, 2, 2, kWhite);  // the top of the 1
  EXPECT_FALSE(FindText(image, "1.40 cm", kFontInk, 2)) << "a glyph partly covered";
}

}  // namespace
}  // namespace evoslam
