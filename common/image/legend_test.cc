#include "common/image/legend.h"

#include <gtest/gtest.h>

#include <vector>

#include "common/image/bitmap_font.h"

namespace evoslam {
namespace {

constexpr Rgb kLegendInk{40, 40, 40};
constexpr Rgb kLegendRed{220, 30, 30};
constexpr Rgb kLegendGreen{0, 160, 0};
constexpr Rgb kLegendOrange{240, 140, 0};
constexpr Rgb kLegendGrey{205, 205, 205};

const std::vector<LegendEntry> kLegendEntries = {
    {"estimate", kLegendRed, LegendMark::kLine, 2},
    {"ground truth", kLegendGreen, LegendMark::kLine, 7},
    {"loop closures (3)", kLegendOrange, LegendMark::kLink, 2},
    {"free", kWhite, LegendMark::kSwatch},
    {"unexplored", kLegendGrey, LegendMark::kSwatch},
};

TEST(LegendTest, EachEntryShowsItsMarkAndItsLabel) {
  const int height = LegendHeight(kLegendEntries, 2000, 2);
  Image image(2000, height + 20, {250, 250, 250});
  DrawLegend(image, 10, 10, 1980, kLegendEntries, kLegendInk, 2);
  for (const LegendEntry& e : kLegendEntries) {
    EXPECT_TRUE(FindText(image, e.label, kLegendInk, 2)) << e.label;
    EXPECT_GT(CountPixels(image, e.color), 20) << e.label;
  }
  EXPECT_GT(CountPixels(image, kLegendGreen), 3 * CountPixels(image, kLegendRed) - 20)
      << "drawn as thick";
  EXPECT_EQ(height, TextHeight(2)) << "one row";
}

TEST(LegendTest, EntriesThatDoNotFitStartANewRow) {
  const int width = 300;
  const int height = LegendHeight(kLegendEntries, width, 2);
  EXPECT_GT(height, 2 * TextHeight(2));
  Image image(width + 20, height + 20);
  DrawLegend(image, 10, 10, width, kLegendEntries, kLegendInk, 2);
  for (const LegendEntry& e : kLegendEntries) {
    const auto at = FindText(image, e.label, kLegendInk, 2);
    ASSERT_TRUE(at) << e.label;
    EXPECT_LE(at->x() + TextWidth(e.label, 2), 10 + width) << e.label;
    EXPECT_LE(at->y() + TextHeight(2), 10 + height) << e.label;
  }
}

TEST(LegendTest, MarkerEntriesShowTheirMarker) {
  const std::vector<LegendEntry> entries = {{"members", kLegendGreen, LegendMark::kDot},
                                            {"chosen", kLegendInk, LegendMark::kRing},
                                            {"start", kLegendRed, LegendMark::kCross}};
  Image image(600, LegendHeight(entries, 600, 2) + 20);
  DrawLegend(image, 10, 10, 580, entries, kLegendInk, 2);
  for (const LegendEntry& e : entries) EXPECT_TRUE(FindText(image, e.label, kLegendInk, 2));
  EXPECT_GT(CountPixels(image, kLegendGreen), 100) << "a dot as tall as the capitals";
  EXPECT_GT(CountPixels(image, kLegendRed), 20);
}

TEST(LegendTest, NoEntriesTakeNoRoom) { EXPECT_EQ(LegendHeight({}, 500, 2), 0); }

}  // namespace
}  // namespace evoslam
