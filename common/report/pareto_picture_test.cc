#include "common/report/pareto_picture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/image/bitmap_font.h"
#include "common/io/file_bytes.h"
#include "common/report/map_picture.h"
#include "common/report/pareto_testing.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using testing::MakeFront;
using testing::TwoWindowFronts;

constexpr std::string_view kParetoRunTitle = "office.clf - SLAM (immune), 241 scans";

Rgb PixelAt(const Image& image, const Eigen::Vector2d& p) {
  return image.at(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
}

// The mean place of the pixels of `color` within the panel's plot area.
Eigen::Vector2d MeanPlaceOf(const Image& image, const PlotAxes& panel, Rgb color) {
  Eigen::Vector2d sum(0, 0);
  int n = 0;
  const Eigen::Vector2i a = panel.area_top_left();
  for (int y = a.y(); y < a.y() + panel.area_size().y(); ++y) {
    for (int x = a.x(); x < a.x() + panel.area_size().x(); ++x) {
      if (!(image.at(x, y) == color)) continue;
      sum += Eigen::Vector2d(x, y);
      ++n;
    }
  }
  EXPECT_GT(n, 0);
  return sum / std::max(n, 1);
}

TEST(ParetoPictureTest, ThreeObjectivesGiveTwoPanelsSideBySideOfASaneSize) {
  const ParetoPicture picture = DrawParetoPicture(TwoWindowFronts(), kParetoRunTitle);
  EXPECT_GE(picture.image.width(), 1000);
  EXPECT_LE(picture.image.width(), 2000);
  EXPECT_GE(picture.image.height(), 500);
  EXPECT_LE(picture.image.height(), 1200);
  ASSERT_EQ(picture.panels.size(), 2u);
  EXPECT_TRUE(picture.relative);
  EXPECT_EQ(picture.panels[0].area_top_left().y(), picture.panels[1].area_top_left().y());
  EXPECT_GT(picture.panels[1].area_top_left().x(),
            picture.panels[0].area_top_left().x() + picture.panels[0].area_size().x());
  EXPECT_TRUE(FindText(picture.image, kParetoRunTitle, kInkColor, 2));
}

TEST(ParetoPictureTest, TheAxesAreNamedByTheObjectives) {
  const Image relative = DrawParetoPicture(TwoWindowFronts(), kParetoRunTitle).image;
  for (const std::string& name : testing::ImmuneObjectives()) {
    EXPECT_TRUE(FindText(relative, name + ", relative to start", kInkColor, 2)) << name;
  }
  std::vector<ParetoFront> absolute = TwoWindowFronts();
  absolute.pop_back();
  absolute[0].start.clear();
  const ParetoPicture picture = DrawParetoPicture(absolute, kParetoRunTitle);
  EXPECT_FALSE(picture.relative);
  for (const std::string& name : testing::ImmuneObjectives()) {
    EXPECT_TRUE(FindText(picture.image, name, kInkColor, 2)) << name;
    EXPECT_FALSE(FindText(picture.image, name + ", relative to start", kInkColor, 2)) << name;
  }
}

TEST(ParetoPictureTest, EachChosenMemberIsRingedWhereTheAxesPutIt) {
  const std::vector<ParetoFront> fronts = TwoWindowFronts();
  const ParetoPicture picture = DrawParetoPicture(fronts, kParetoRunTitle);
  for (std::size_t i = 0; i < fronts.size(); ++i) {
    const ParetoFront& front = fronts[i];
    const auto c = static_cast<Eigen::Index>(front.chosen);
    for (std::size_t k = 0; k < picture.panels.size(); ++k) {
      const auto o = static_cast<Eigen::Index>(k) + 1;
      const Eigen::Vector2d relative(front.f(0, c) / front.start[0],
                                     front.f(o, c) / front.start[static_cast<std::size_t>(o)]);
      const Eigen::Vector2d p = picture.panels[k].ToPixel(relative);
      EXPECT_EQ(PixelAt(picture.image, p), ParetoFrontColor(i, fronts.size())) << i << " " << k;
      const std::vector<Eigen::Vector2d> ring = {{8, 0}, {-8, 0}, {0, 8}, {0, -8}};
      for (const Eigen::Vector2d& d : ring) {
        EXPECT_EQ(PixelAt(picture.image, p + d), kInkColor) << i << " " << k << " " << d.x();
      }
    }
  }
}

TEST(ParetoPictureTest, MembersBetterThanTheStartLieLeftOfAndBelowItsMark) {
  const std::vector<ParetoFront> fronts = {TwoWindowFronts()[0]};
  const ParetoPicture picture = DrawParetoPicture(fronts, kParetoRunTitle);
  const Rgb color = ParetoFrontColor(0, 1);
  for (const PlotAxes& panel : picture.panels) {
    const Eigen::Vector2d start = MeanPlaceOf(picture.image, panel, kParetoStartColor);
    EXPECT_NEAR((start - panel.ToPixel({1.0, 1.0})).norm(), 0.0, 1.0) << "the start at (1, 1)";
    const Eigen::Vector2d members = MeanPlaceOf(picture.image, panel, color);
    EXPECT_LT(members.x(), start.x() - 20);
    EXPECT_GT(members.y(), start.y() + 20) << "rows run down";
  }
  // A front that ended worse in the third objective lies above the start in that panel alone.
  std::vector<ParetoFront> worse = fronts;
  worse[0].f.row(2).array() += 1000.0;
  const ParetoPicture other = DrawParetoPicture(worse, kParetoRunTitle);
  const Eigen::Vector2d start = MeanPlaceOf(other.image, other.panels[1], kParetoStartColor);
  EXPECT_LT(MeanPlaceOf(other.image, other.panels[1], color).y(), start.y() - 20);
}

TEST(ParetoPictureTest, FrontsWithoutStartsAreDrawnAsTheyAre) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  for (ParetoFront& f : fronts) f.start.clear();
  const ParetoPicture picture = DrawParetoPicture(fronts, kParetoRunTitle);
  EXPECT_FALSE(picture.relative);
  EXPECT_EQ(CountPixels(picture.image, kParetoStartColor), 0) << "no start to mark";
  for (std::size_t i = 0; i < fronts.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(fronts[i].chosen);
    const Eigen::Vector2d p = picture.panels[0].ToPixel({fronts[i].f(0, c), fronts[i].f(1, c)});
    EXPECT_EQ(PixelAt(picture.image, p), ParetoFrontColor(i, fronts.size()));
  }
}

TEST(ParetoPictureTest, FewFrontsAreNamedAndManyShownAsAGradient) {
  const Image few = DrawParetoPicture(TwoWindowFronts(), kParetoRunTitle).image;
  for (const ParetoFront& f : TwoWindowFronts()) {
    EXPECT_TRUE(FindText(few, f.label, kInkColor, 2)) << f.label;
  }
  EXPECT_TRUE(FindText(few, "the member chosen", kInkColor, 2));
  EXPECT_TRUE(FindText(few, "where each search started", kInkColor, 2));

  std::vector<ParetoFront> many;
  for (int i = 0; i < 30; ++i) {
    ParetoFront f = TwoWindowFronts()[static_cast<std::size_t>(i % 2)];
    f.label = "window " + std::to_string(i);
    f.f *= 1.0 - 0.005 * i;  // so that no front hides another
    many.push_back(f);
  }
  const Image image = DrawParetoPicture(many, kParetoRunTitle).image;
  EXPECT_TRUE(FindText(image, "fronts in order:", kInkColor, 2));
  EXPECT_TRUE(FindText(image, "window 0", kInkColor, 2));
  EXPECT_TRUE(FindText(image, "window 29", kInkColor, 2));
  EXPECT_FALSE(FindText(image, "window 15", kInkColor, 2)) << "no entry a front";
  for (const std::size_t i : {0u, 15u, 29u}) {
    EXPECT_GT(CountPixels(image, ParetoFrontColor(i, many.size())), 0) << i;
  }
  EXPECT_NE(ParetoFrontColor(0, 30), ParetoFrontColor(29, 30));
}

TEST(ParetoPictureTest, OneObjectiveShowsEachFrontsChosenValueAgainstItsStart) {
  const std::vector<std::string> sum = {"weighted sum"};
  const std::vector<ParetoFront> fronts = {MakeFront("window 0", {{80.0}}, {100.0}, 0, sum),
                                           MakeFront("window 1", {{130.0}}, {100.0}, 0, sum),
                                           MakeFront("window 2", {{-4.0}}, {-2.0}, 0, sum)};
  const ParetoPicture picture = DrawParetoPicture(fronts, kParetoRunTitle);
  ASSERT_EQ(picture.panels.size(), 1u);
  EXPECT_TRUE(picture.relative);
  const PlotAxes& panel = picture.panels[0];
  EXPECT_TRUE(FindText(picture.image, "weighted sum, relative to start", kInkColor, 2));
  EXPECT_TRUE(FindText(picture.image, "front, in the order the searches ran", kInkColor, 2));
  // Each bar from 1 to the chosen value: a fifth lower, three tenths higher, twice as far down.
  EXPECT_EQ(PixelAt(picture.image, panel.ToPixel({0.0, 0.9})), kParetoBetterColor);
  EXPECT_EQ(PixelAt(picture.image, panel.ToPixel({1.0, 1.15})), kParetoWorseColor);
  EXPECT_EQ(PixelAt(picture.image, panel.ToPixel({2.0, 0.5})), kParetoBetterColor);
  EXPECT_EQ(PixelAt(picture.image, panel.ToPixel({2.0, 0.05})), kParetoBetterColor);
  EXPECT_NE(PixelAt(picture.image, panel.ToPixel({0.0, 0.7})), kParetoBetterColor) << "past 0.8";
  EXPECT_NE(PixelAt(picture.image, panel.ToPixel({1.0, 0.9})), kParetoWorseColor);
  EXPECT_EQ(PixelAt(picture.image, panel.ToPixel({0.5, 1.0})), kParetoStartColor);

  // Without starts the chosen values stand as they are.
  std::vector<ParetoFront> bare = fronts;
  for (ParetoFront& f : bare) f.start.clear();
  const ParetoPicture absolute = DrawParetoPicture(bare, kParetoRunTitle);
  EXPECT_FALSE(absolute.relative);
  EXPECT_EQ(PixelAt(absolute.image, absolute.panels[0].ToPixel({1.0, 130.0})), kParetoBetterColor);
}

TEST(ParetoPictureTest, NonFiniteValuesAreLeftOutAndCounted) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  fronts[0].f(2, 0) = std::numeric_limits<double>::quiet_NaN();
  fronts[1].f(1, 1) = std::numeric_limits<double>::infinity();
  const ParetoPicture picture = DrawParetoPicture(fronts, kParetoRunTitle);
  EXPECT_TRUE(FindText(picture.image, "2 members left out, not finite", kInkColor, 2));
  // The member with one value left out is not drawn in the panel whose values it has either.
  const Eigen::Vector2d p = picture.panels[0].ToPixel(
      {fronts[0].f(0, 0) / fronts[0].start[0], fronts[0].f(1, 0) / fronts[0].start[1]});
  EXPECT_NE(PixelAt(picture.image, p), ParetoFrontColor(0, 2));
}

TEST(ParetoPictureTest, FrontsThatDoNotMatchAreRefused) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  fronts[1].objectives = {"consistency", "occupied cells", "free cells"};
  EXPECT_THROW(DrawParetoPicture(fronts, kParetoRunTitle), Error);
  fronts = TwoWindowFronts();
  fronts[0].start = {1.0, std::numeric_limits<double>::quiet_NaN(), 1.0};
  EXPECT_THROW(DrawParetoPicture(fronts, kParetoRunTitle), Error);
}

TEST(ParetoPictureTest, TheSameFrontsGiveTheSameBytes) {
  const TempDir dir;
  WriteParetoPicture(TwoWindowFronts(), kParetoRunTitle, dir / "a.png");
  WriteParetoPicture(TwoWindowFronts(), kParetoRunTitle, dir / "b.png");
  EXPECT_TRUE(ReadFileBytes(dir / "a.png") == ReadFileBytes(dir / "b.png"));
  const Image written = ReadPng(dir / "a.png");
  const Image drawn = DrawParetoPicture(TwoWindowFronts(), kParetoRunTitle).image;
  ASSERT_EQ(written.width(), drawn.width());
  ASSERT_EQ(written.height(), drawn.height());
  for (int y = 0; y < drawn.height(); ++y) {
    for (int x = 0; x < drawn.width(); ++x) ASSERT_EQ(written.at(x, y), drawn.at(x, y));
  }
}

}  // namespace
}  // namespace evoslam
