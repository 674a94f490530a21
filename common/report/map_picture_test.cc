#include "common/report/map_picture.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/image/image.h"
#include "common/localization/test_scenes.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

class MapPictureTest : public ::testing::Test {
 protected:
  TempDir dir_;
  std::filesystem::path path_ = dir_ / "map.png";
};

TEST_F(MapPictureTest, DrawsWallsAndEveryTrajectoryInItsColour) {
  const MapModel map(testing::BoxRoom());
  const Rgb red{220, 30, 30};
  const Rgb green{0, 160, 0};
  const std::vector<TrajectoryLayer> layers = {
      {"truth", {Pose2(1, 1, 0), Pose2(3, 1, 0), Pose2(3, 5, 1.5)}, green},
      {"estimate", {Pose2(1.2, 1.1, 0), Pose2(4, 2, 0)}, red},
  };
  WriteMapPicture(map, layers, path_, 400);
  const Image image = ReadPng(path_);
  // The 6 x 8 m room fills the longer side.
  EXPECT_LE(std::max(image.width(), image.height()), 402);
  EXPECT_GE(std::max(image.width(), image.height()), 390);
  EXPECT_GT(image.height(), image.width());
  EXPECT_GT(CountPixels(image, {0, 0, 0}), 400) << "walls";
  EXPECT_GT(CountPixels(image, green), 100);
  EXPECT_GT(CountPixels(image, red), 50);
}

TEST_F(MapPictureTest, TrajectoryOutsideTheMapStaysInThePicture) {
  const MapModel map(testing::BoxRoom());
  const Rgb blue{0, 0, 255};
  const std::vector<TrajectoryLayer> layers = {{"far", {Pose2(20, 20, 0), Pose2(21, 20, 0)}, blue}};
  WriteMapPicture(map, layers, path_, 300);
  EXPECT_GT(CountPixels(ReadPng(path_), blue), 10);
}

TEST_F(MapPictureTest, UnwritablePathIsAnError) {
  EXPECT_THROW(WriteMapPicture(MapModel(testing::BoxRoom()), {}, "/nonexistent-dir/map.png"),
               Error);
}

}  // namespace
}  // namespace evoslam
