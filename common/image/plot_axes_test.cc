#include "common/image/plot_axes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "common/image/bitmap_font.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr Rgb kAxesInk{40, 40, 40};
constexpr Rgb kAxesGrid{225, 225, 225};

// Whether the step is 1, 2 or 5 times a power of ten.
bool IsRoundStep(double step) {
  const double power = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (std::abs(step - m * power) <= 1e-9 * step) return true;
  }
  return false;
}

// How many multiples of `step` lie within the axis.
long long MultiplesWithin(const PlotAxis& axis, double step) {
  return static_cast<long long>(std::floor(axis.max / step) - std::ceil(axis.min / step)) + 1;
}

TEST(PlotAxesTest, TicksAreTheFinestRoundMultiplesThatAreFewEnough) {
  for (const PlotAxis& axis :
       {PlotAxis{0.93, 1.07, "", false}, PlotAxis{-3.0, 250.0, "", false},
        PlotAxis{12000.0, 48000.0, "", false}, PlotAxis{1e-7, 3e-6, "", false}}) {
    for (const int most : {2, 5, 8}) {
      const PlotTicks ticks = MakePlotTicks(axis, most);
      ASSERT_FALSE(ticks.values.empty()) << axis.min << " " << most;
      EXPECT_LE(static_cast<int>(ticks.values.size()), most);
      EXPECT_TRUE(IsRoundStep(ticks.step)) << ticks.step;
      for (const double v : ticks.values) {
        EXPECT_GE(v, axis.min);
        EXPECT_LE(v, axis.max);
        EXPECT_NEAR(v / ticks.step, std::round(v / ticks.step), 1e-9);
      }
      // The next finer round step would give too many.
      const double finer = IsRoundStep(ticks.step / 2) ? ticks.step / 2 : ticks.step / 2.5;
      EXPECT_GT(MultiplesWithin(axis, finer), most) << ticks.step;
    }
  }
}

TEST(PlotAxesTest, AWholeAxisTicksWholeNumbersOnly) {
  const PlotTicks ticks = MakePlotTicks({-0.5, 3.5, "front", true}, 20);
  EXPECT_EQ(ticks.values, (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(ticks.texts, (std::vector<std::string>{"0", "1", "2", "3"}));
}

TEST(PlotAxesTest, TickTextsReadBackAsTheirTicksAndDiffer) {
  for (const PlotAxis& axis :
       {PlotAxis{0.9981, 1.0012, "", false}, PlotAxis{0.05, 0.45, "", false},
        PlotAxis{1.2e6, 4.9e6, "", false}, PlotAxis{-2e-10, 3e-10, "", false}}) {
    const PlotTicks ticks = MakePlotTicks(axis, 6);
    ASSERT_GE(ticks.values.size(), 2u);
    const std::set<std::string> distinct(ticks.texts.begin(), ticks.texts.end());
    EXPECT_EQ(distinct.size(), ticks.texts.size());
    for (std::size_t i = 0; i < ticks.values.size(); ++i) {
      EXPECT_NEAR(std::stod(ticks.texts[i]), ticks.values[i], 1e-6 * ticks.step) << ticks.texts[i];
      EXPECT_LE(ticks.texts[i].size(), 10u) << ticks.texts[i];
    }
  }
  EXPECT_EQ(MakePlotTicks({0.93, 1.07, "", false}, 3).texts,
            (std::vector<std::string>{"0.95", "1.00", "1.05"}));
}

TEST(PlotAxesTest, BadAxesAreErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MakePlotTicks({1.0, 1.0, "", false}, 5), Error);
  EXPECT_THROW(MakePlotTicks({2.0, 1.0, "", false}, 5), Error);
  EXPECT_THROW(MakePlotTicks({nan, 1.0, "", false}, 5), Error);
  EXPECT_THROW(MakePlotTicks({-1e308, 1e308, "", false}, 5), Error) << "a span past a double";
  EXPECT_THROW(MakePlotTicks({0.0, 1.0, "", false}, 0), Error);
  EXPECT_THROW(PaddedAxis(1.0, 0.0, 0.05, ""), Error);
  EXPECT_THROW(PaddedAxis(0.0, std::numeric_limits<double>::infinity(), 0.05, ""), Error);
  EXPECT_THROW(PaddedAxis(0.0, 1.0, -0.1, ""), Error);
}

TEST(PlotAxesTest, APaddedAxisHoldsItsValuesClearOfItsEnds) {
  const PlotAxis axis = PaddedAxis(2.0, 6.0, 0.05, "x");
  EXPECT_DOUBLE_EQ(axis.min, 1.8);
  EXPECT_DOUBLE_EQ(axis.max, 6.2);
  EXPECT_EQ(axis.label, "x");
  for (const double single : {0.0, 1.0, -250.0}) {
    const PlotAxis around = PaddedAxis(single, single, 0.05, "");
    EXPECT_LT(around.min, single);
    EXPECT_GT(around.max, single);
    EXPECT_NEAR(around.max - single, single - around.min, 1e-12);
  }
}

class PlotAxesDrawTest : public ::testing::Test {
 protected:
  const PlotAxes axes{{30, 20},
                      {600, 400},
                      PaddedAxis(0.9, 1.1, 0.0, "consistency / start"),
                      PaddedAxis(100.0, 500.0, 0.0, "occupied cells"),
                      2};
};

TEST_F(PlotAxesDrawTest, TheAxesEndsLieOnTheAreasOutermostPixels) {
  const Eigen::Vector2i a = axes.area_top_left();
  const Eigen::Vector2i n = axes.area_size();
  EXPECT_GE(a.x(), 30);
  EXPECT_GE(a.y(), 20);
  EXPECT_LE(a.x() + n.x(), 30 + 600);
  EXPECT_LE(a.y() + n.y(), 20 + 400);
  EXPECT_GT(n.x(), 400);
  EXPECT_GT(n.y(), 250);
  const Eigen::Vector2d low = axes.ToPixel({axes.x().min, axes.y().min});
  const Eigen::Vector2d high = axes.ToPixel({axes.x().max, axes.y().max});
  EXPECT_DOUBLE_EQ(low.x(), a.x());
  EXPECT_DOUBLE_EQ(low.y(), a.y() + n.y() - 1);
  EXPECT_DOUBLE_EQ(high.x(), a.x() + n.x() - 1);
  EXPECT_DOUBLE_EQ(high.y(), a.y());
  const Eigen::Vector2d middle = axes.ToPixel({1.0, 300.0});
  EXPECT_NEAR(middle.x(), (low.x() + high.x()) / 2, 1e-9);
  EXPECT_NEAR(middle.y(), (low.y() + high.y()) / 2, 1e-9);
}

TEST_F(PlotAxesDrawTest, EachTicksNumberStandsAtItsTick) {
  Image image(700, 450);
  axes.Draw(image, kAxesInk, kAxesGrid);
  ASSERT_GE(axes.x_ticks().values.size(), 3u);
  ASSERT_GE(axes.y_ticks().values.size(), 3u);
  const Eigen::Vector2i a = axes.area_top_left();
  const Eigen::Vector2i n = axes.area_size();
  for (std::size_t i = 0; i < axes.x_ticks().values.size(); ++i) {
    const std::string& text = axes.x_ticks().texts[i];
    const auto at = FindText(image, text, kAxesInk, 2);
    ASSERT_TRUE(at) << text;
    const double px = axes.ToPixel({axes.x_ticks().values[i], 0.0}).x();
    EXPECT_NEAR(at->x() + TextWidth(text, 2) / 2.0, px, 2.0) << text;
    EXPECT_GT(at->y(), a.y() + n.y()) << "under the frame";
    EXPECT_EQ(image.at(static_cast<int>(std::lround(px)), a.y() + n.y() / 2), kAxesGrid) << text;
  }
  for (std::size_t i = 0; i < axes.y_ticks().values.size(); ++i) {
    const std::string& text = axes.y_ticks().texts[i];
    const auto at = FindText(image, text, kAxesInk, 2);
    ASSERT_TRUE(at) << text;
    const double py = axes.ToPixel({0.0, axes.y_ticks().values[i]}).y();
    EXPECT_NEAR(at->y() + TextHeight(2) / 2.0, py, 4.0) << text;
    EXPECT_LT(at->x() + TextWidth(text, 2), a.x()) << "left of the frame";
  }
}

TEST_F(PlotAxesDrawTest, TheFrameAndTheAxesNamesAreDrawn) {
  Image image(700, 450);
  axes.Draw(image, kAxesInk, kAxesGrid);
  const Eigen::Vector2i a = axes.area_top_left();
  const Eigen::Vector2i n = axes.area_size();
  EXPECT_EQ(image.at(a.x() - 1, a.y() + 5), kAxesInk);
  EXPECT_EQ(image.at(a.x() + n.x(), a.y() + 5), kAxesInk);
  EXPECT_EQ(image.at(a.x() + 3, a.y() - 1), kAxesInk);
  EXPECT_EQ(image.at(a.x() + 3, a.y() + n.y()), kAxesInk);
  const auto x_name = FindText(image, "consistency / start", kAxesInk, 2);
  ASSERT_TRUE(x_name);
  EXPECT_GT(x_name->y(), a.y() + n.y() + TextHeight(2)) << "under the numbers";
  const auto y_name = FindText(image, "occupied cells", kAxesInk, 2);
  ASSERT_TRUE(y_name);
  EXPECT_LT(y_name->y() + TextHeight(2), a.y()) << "over the area";
}

TEST(PlotAxesTest, ABoxTooSmallIsAnError) {
  EXPECT_THROW(PlotAxes({0, 0}, {80, 60}, PaddedAxis(0, 1, 0, "x"), PaddedAxis(0, 1, 0, "y"), 2),
               Error);
  EXPECT_THROW(PlotAxes({0, 0}, {600, 400}, PaddedAxis(0, 1, 0, "x"), PaddedAxis(0, 1, 0, "y"), 0),
               Error);
}

}  // namespace
}  // namespace evoslam
