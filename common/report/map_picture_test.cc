#include "common/report/map_picture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/grid/grid_image.h"
#include "common/image/bitmap_font.h"
#include "common/image/image.h"
#include "common/localization/test_scenes.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

constexpr Rgb kFrame{150, 150, 150};

struct Box {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive; empty when x1 < x0
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
  bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

// The smallest box around the pixels of this colour within `within` (all the image if empty).
Box BoxOf(const Image& image, Rgb color, Box within = {}) {
  if (within.x1 < within.x0) within = {0, 0, image.width() - 1, image.height() - 1};
  Box b{image.width(), image.height(), -1, -1};
  for (int y = within.y0; y <= within.y1; ++y) {
    for (int x = within.x0; x <= within.x1; ++x) {
      if (!(image.at(x, y) == color)) continue;
      b = {std::min(b.x0, x), std::min(b.y0, y), std::max(b.x1, x), std::max(b.y1, y)};
    }
  }
  return b;
}

// The map area, inside its outline.
Box MapArea(const Image& image) {
  const Box outline = BoxOf(image, kFrame);
  return {outline.x0 + 1, outline.y0 + 1, outline.x1 - 1, outline.y1 - 1};
}

int CountIn(const Image& image, const Box& box, Rgb color) {
  int n = 0;
  for (int y = std::max(0, box.y0); y <= std::min(image.height() - 1, box.y1); ++y) {
    for (int x = std::max(0, box.x0); x <= std::min(image.width() - 1, box.x1); ++x) {
      n += image.at(x, y) == color;
    }
  }
  return n;
}

// A walk round BoxRoom with turns.
std::vector<Pose2> Walk() {
  std::vector<Pose2> poses;
  for (int i = 0; i <= 40; ++i) poses.emplace_back(1.0 + 0.1 * i, 2.0, 0.0);
  for (int i = 1; i <= 40; ++i) poses.emplace_back(5.0, 2.0 + 0.12 * i, 1.57);
  for (int i = 1; i <= 30; ++i) poses.emplace_back(5.0 - 0.1 * i, 6.8, 3.14);
  return poses;
}

// Walk() as odometry that drifts far from the room.
std::vector<Pose2> DriftingOdometry() {
  std::vector<Pose2> poses = Walk();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    poses[i] = Pose2(poses[i].x() + 2.0 * i, poses[i].y() + 1.5 * i, poses[i].theta());
  }
  return poses;
}

// Walls of a 12 x 9 m room at 5 cm cells, free inside, as a SLAM map.
OccupancyGrid RoomGrid(double cell = 0.05) {
  OccupancyGrid grid(cell, {-5.0, -5.0}, static_cast<int>(22 / cell), static_cast<int>(19 / cell));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const Eigen::Vector2d p = grid.CellToWorld(x, y);
      if (p.x() < 0 || p.x() > 12 || p.y() < 0 || p.y() > 9) continue;
      const bool wall = p.x() < 0.2 || p.x() > 11.8 || p.y() < 0.2 || p.y() > 8.8;
      grid.SetCell(x, y, wall ? CellState::kOccupied : CellState::kFree);
    }
  }
  return grid;
}

MapPictureContent Everything() {
  MapPictureContent c;
  c.title = "office.clf - SLAM (rss), 111 scans - aligned RMS error 1.40 cm against ground truth";
  c.layers = {{LayerKind::kOdometry, "odometry alone", DriftingOdometry()},
              {LayerKind::kTruth, "ground truth", Walk()},
              {LayerKind::kEstimate, "estimate", Walk()}};
  c.shows_loops = true;
  c.loops = {{{1.0, 2.0}, {4.0, 2.0}}, {{5.0, 3.0}, {5.0, 6.0}}};
  return c;
}

TEST(MapPictureTest, DrawsWallsAndEveryTrajectoryInItsColour) {
  MapPictureContent c;
  std::vector<Pose2> beside = Walk();
  for (Pose2& p : beside) p = Pose2(p.x() + 0.5, p.y() + 0.5, p.theta());
  c.layers = {{LayerKind::kTruth, "ground truth", Walk()},
              {LayerKind::kCompared, "other run", beside},
              {LayerKind::kEstimate, "estimate", Walk()}};
  const Image image = DrawMapPicture(MapModel(testing::BoxRoom()), c);
  EXPECT_GT(CountPixels(image, kOccupiedCellColor), 1000) << "walls";
  EXPECT_GT(CountPixels(image, kTruthColor), 1000);
  EXPECT_GT(CountPixels(image, kComparedColor), 1000);
  EXPECT_GT(CountPixels(image, kEstimateColor), 500);
  // The 6 x 8 m room stands upright.
  const Box walls = BoxOf(image, kOccupiedCellColor, MapArea(image));
  EXPECT_NEAR(static_cast<double>(walls.height()) / walls.width(), 8.0 / 6.0, 0.02);
}

// At least 1,000 pixels on the long side, for a room of a metre or of a hundred, in any cells.
TEST(MapPictureTest, TheLongSideHasAThousandPixelsWhateverTheSizeAndCells) {
  for (const double cell : {0.02, 0.5, 2.0}) {
    const Image image = DrawMapPicture(MapModel(RoomGrid(cell)), {});
    EXPECT_GE(std::max(image.width(), image.height()), 1000) << cell;
  }
  for (const double side : {1.0, 100.0}) {
    const LineMap room(
        std::vector<Segment>{{{0.0, 0.0}, {side, 0.0}}, {{side, 0.0}, {side, side / 3}}});
    const Image image = DrawMapPicture(MapModel(room), {});
    EXPECT_GE(std::max(image.width(), image.height()), 1000) << side;
    EXPECT_GE(BoxOf(image, kOccupiedCellColor, MapArea(image)).width(), 1000) << side;
  }
}

// Odometry that drifts 200 m off a 6 x 8 m room neither moves the frame nor leaves it: the room
// fills the map area, and odometry ends at the frame, faded.
TEST(MapPictureTest, OdometryOffTheMapIsClippedAtTheFrameAndLeavesTheMapItsRoom) {
  MapPictureContent c;
  c.layers = {{LayerKind::kOdometry, "odometry alone", DriftingOdometry()},
              {LayerKind::kEstimate, "estimate", Walk()}};
  const Image image = DrawMapPicture(MapModel(testing::BoxRoom()), c);
  const Box frame = MapArea(image);
  const Box walls = BoxOf(image, kOccupiedCellColor, frame);
  EXPECT_GT(walls.height(), 0.9 * frame.height());
  EXPECT_GT(walls.height(), 0.6 * image.height());
  const int odometry = CountPixels(image, kOdometryColor);
  EXPECT_GT(odometry, 200);
  // Within the frame, bar the legend's stroke.
  EXPECT_GT(CountIn(image, frame, kOdometryColor), odometry - 200);
  Box legend = frame;
  legend.y0 = frame.y1 + 1;
  legend.y1 = image.height() - 1;
  legend.x0 = 0;
  legend.x1 = image.width() - 1;
  EXPECT_EQ(CountIn(image, frame, kOdometryColor) + CountIn(image, legend, kOdometryColor),
            odometry);
  EXPECT_GT(kOdometryColor.r + kOdometryColor.g + kOdometryColor.b, 3 * 150) << "faded";
}

// An estimate that is the truth leaves a band of the truth on both sides of it.
TEST(MapPictureTest, TheTruthShowsUnderAnEstimateThatFollowsIt) {
  MapPictureContent c;
  c.layers = {{LayerKind::kEstimate, "estimate", Walk()},
              {LayerKind::kTruth, "ground truth", Walk()}};
  const Image image = DrawMapPicture(MapModel(testing::BoxRoom()), c);
  const int truth = CountPixels(image, kTruthColor);
  const int estimate = CountPixels(image, kEstimateColor);
  EXPECT_GT(estimate, 500);
  EXPECT_GT(truth, 2 * estimate);
  // On each side of the estimate's straight stretches.
  const Box area = MapArea(image);
  int above = 0;
  int below = 0;
  for (int x = area.x0 + area.width() / 4; x < area.x0 + area.width() / 2; ++x) {
    for (int y = area.y0; y <= area.y1; ++y) {
      if (!(image.at(x, y) == kEstimateColor)) continue;
      above += image.at(x, y - 2) == kTruthColor;
      below += image.at(x, y + 2) == kTruthColor;
      break;
    }
  }
  EXPECT_GT(above, 50);
  EXPECT_GT(below, 50);
}

// Each layer, the loops and the map's colours are named under the map, beside their marks.
TEST(MapPictureTest, TheLegendNamesEveryLayerTheLoopsAndTheMapsColours) {
  const Image image = DrawMapPicture(MapModel(RoomGrid()), Everything());
  const Box frame = MapArea(image);
  const struct {
    const char* label;
    Rgb color;
  } entries[] = {{"estimate", kEstimateColor},       {"ground truth", kTruthColor},
                 {"odometry alone", kOdometryColor}, {"loop closures (2)", kLoopColor},
                 {"occupied", kOccupiedCellColor},   {"free", kFreeCellColor},
                 {"unexplored", kUnknownCellColor}};
  // The title names some of them too.
  Image under(image.width(), image.height() - frame.y1 - 1);
  under.Paste(image, 0, -frame.y1 - 1);
  for (const auto& e : entries) {
    const auto at = FindText(under, e.label, kInkColor, 2);
    ASSERT_TRUE(at) << e.label;
    const Box mark{at->x() - 40, at->y(), at->x() - 1, at->y() + TextHeight(2)};
    EXPECT_GT(CountIn(under, mark, e.color), 10) << e.label;
  }
}

TEST(MapPictureTest, TheTitleStandsOverTheMap) {
  const MapPictureContent c = Everything();
  const Image image = DrawMapPicture(MapModel(RoomGrid()), c);
  const auto at = FindText(image, c.title, kInkColor, 2);
  ASSERT_TRUE(at);
  EXPECT_LT(at->y() + TextHeight(2), MapArea(image).y0);

  // A title too long for one line goes on over several.
  MapPictureContent wordy = c;
  wordy.title = c.title + " " + c.title + " " + c.title;
  const Image wrapped = DrawMapPicture(MapModel(RoomGrid()), wordy);
  const std::vector<std::string> lines = WrapText(wordy.title, wrapped.width() - 32, 2);
  ASSERT_GT(lines.size(), 1u);
  for (const std::string& line : lines) EXPECT_TRUE(FindText(wrapped, line, kInkColor, 2)) << line;
}

// The bar's length in pixels, at the map's scale, is the round number of metres its label says.
TEST(MapPictureTest, TheScaleBarMeasuresMetres) {
  const Image image = DrawMapPicture(MapModel(testing::BoxRoom()), {});
  const Box frame = MapArea(image);
  const Box walls = BoxOf(image, kOccupiedCellColor, frame);
  // The 8 m walls, drawn 2 pixels wide.
  const double metres_per_pixel = 8.0 / (walls.height() - 2);
  int longest = 0;
  for (int y = frame.y1 + 1; y < image.height(); ++y) {
    int run = 0;
    for (int x = 0; x < image.width(); ++x) {
      run = image.at(x, y) == kInkColor ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  const double metres = longest * metres_per_pixel;
  const double power = std::pow(10.0, std::floor(std::log10(metres)));
  double round = 0.0;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (std::abs(metres - m * power) < 0.02 * metres) round = m * power;
  }
  ASSERT_GT(round, 0.0) << metres << " m is not a round length";
  char label[32];
  std::snprintf(label, sizeof label, "%g m", round);
  EXPECT_TRUE(FindText(image, label, kInkColor, 2)) << label;
}

// A return 5 m off the room and the free streak of a beam through a door are clipped, not framed.
TEST(MapPictureTest, StrayReturnsAndFreeStreaksDoNotSetTheFrame) {
  OccupancyGrid grid = RoomGrid();
  const auto stray = grid.WorldToCell({-4.5, -4.5});
  grid.SetCell(stray->x(), stray->y(), CellState::kOccupied);
  for (double x = 12.0; x < 16.5; x += 0.05) {
    const auto streak = grid.WorldToCell({x, 4.5});
    grid.SetCell(streak->x(), streak->y(), CellState::kFree);
  }
  const Image image = DrawMapPicture(MapModel(grid), {});
  const Box area = MapArea(image);
  const Box walls = BoxOf(image, kOccupiedCellColor, area);
  EXPECT_GT(walls.width(), 0.9 * area.width());
  EXPECT_GT(walls.height(), 0.9 * area.height());
}

TEST(MapPictureTest, AnEmptyGridIsFramedWhole) {
  const OccupancyGrid grid(0.1, {0.0, 0.0}, 50, 30);
  const Image image = DrawMapPicture(MapModel(grid), {});
  // 5 x 3 m and a margin of 3 % of the longer side all round.
  const Box frame = MapArea(image);
  EXPECT_NEAR(static_cast<double>(frame.width()) / frame.height(), 5.3 / 3.3, 0.01);
}

TEST(MapPictureTest, UnwritablePathIsAnError) {
  EXPECT_THROW(WriteMapPicture(MapModel(testing::BoxRoom()), {}, "/nonexistent-dir/map.png"),
               Error);
}

TEST(MapPictureTest, WritesThePictureItDraws) {
  const TempDir dir;
  const MapModel map(testing::BoxRoom());
  WriteMapPicture(map, Everything(), dir / "map.png");
  const Image drawn = DrawMapPicture(map, Everything());
  const Image back = ReadPng(dir / "map.png");
  ASSERT_EQ(back.width(), drawn.width());
  ASSERT_EQ(back.height(), drawn.height());
  EXPECT_EQ(CountPixels(back, kTruthColor), CountPixels(drawn, kTruthColor));
}

}  // namespace
}  // namespace evoslam
