#include "common/report/run_pictures.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/grid/map_io.h"
#include "common/image/bitmap_font.h"
#include "common/image/image.h"
#include "common/io/file_bytes.h"
#include "common/line_map/line_map.h"
#include "common/localization/test_scenes.h"
#include "common/report/localize_report.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"
#include "evoslam/localize.pb.h"
#include "evoslam/slam.pb.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;

std::vector<StampedPose> Line(int n, double y) {
  std::vector<StampedPose> poses;
  for (int i = 0; i < n; ++i) poses.push_back({100.0 + i, Pose2(1.0 + 0.1 * i, y, 0.0)});
  return poses;
}

// A folder as a SLAM run over `scans` scans writes it, its estimate along y = `y`.
void WriteSlamRun(const fs::path& dir, int scans, double y) {
  fs::create_directories(dir);
  proto::SlamReport report;
  report.mutable_params()->set_method("rss");
  report.mutable_params()->set_log("office.clf");
  report.set_scans(scans);
  report.mutable_absolute_errors()->set_aligned_rms_translation_m(0.0123);
  proto::LoopClosureRecord& loop = *report.add_loops();
  loop.set_earlier(2);
  loop.set_later(scans - 1);
  WriteJson(report, dir / "report.json");
  WriteTrajectoryText(Line(scans, y), dir / "trajectory.txt");
  WriteTrajectoryText(Line(scans, y + 0.5), dir / "odometry.txt");
  WriteTrajectoryText(Line(scans, y - 0.1), dir / "truth.txt");
  OccupancyGrid grid(0.1, {0.0, 0.0}, 60, 80);
  for (int x = 0; x < 60; ++x) grid.SetCell(x, 10, CellState::kOccupied);
  WriteMapYaml(grid, dir / "map.yaml");
}

// A folder as a localization in walls writes it.
void WriteLocalizeRun(const fs::path& dir) {
  fs::create_directories(dir);
  proto::LocalizeReport report;
  report.mutable_params()->set_log("sim/log.clf");
  report.mutable_params()->set_map("sim/world.lines");
  report.mutable_params()->set_optimizer("de");
  report.mutable_params()->set_fitness("f3");
  report.set_scans(20);
  report.mutable_relation_errors()->set_relations(19);
  report.mutable_relation_errors()->set_translation_mean_m(0.0114);
  report.mutable_relation_errors()->set_translation_std_m(0.0073);
  report.mutable_relation_errors()->set_source("sim.relations");
  WriteJson(report, dir / "report.json");
  WriteTrajectoryText(Line(20, 3.0), dir / "trajectory.txt");
  WriteLineMap(testing::BoxRoom(), dir / "map.lines");
}

class RunPicturesTest : public ::testing::Test {
 protected:
  // Expects ReadRun to refuse the folder with a message naming it and `what`.
  void ExpectRefused(const fs::path& dir, const std::string& what) {
    try {
      ReadRun(dir);
      ADD_FAILURE() << "read " << dir;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
      EXPECT_NE(message.find(what), std::string::npos) << message;
    }
  }

  TempDir dir_;
  const fs::path slam_ = dir_ / "slam";
  const fs::path localize_ = dir_ / "localize";
};

TEST_F(RunPicturesTest, ReadsASlamRunsFolder) {
  WriteSlamRun(slam_, 30, 2.0);
  const RunRecord run = ReadRun(slam_);
  EXPECT_TRUE(run.slam);
  EXPECT_EQ(run.title,
            "office.clf - SLAM (rss), 30 scans - aligned RMS error 1.23 cm against "
            "ground truth");
  EXPECT_EQ(run.error, "1.23 cm aligned RMS");
  ASSERT_TRUE(run.map.grid());
  EXPECT_EQ(run.map.grid()->width(), 60);
  EXPECT_EQ(run.estimate.size(), 30u);
  EXPECT_EQ(run.odometry.size(), 30u);
  EXPECT_EQ(run.truth.size(), 30u);
  ASSERT_EQ(run.loops.size(), 1u);
  EXPECT_NEAR((run.loops[0].earlier - Eigen::Vector2d(1.2, 2.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((run.loops[0].later - Eigen::Vector2d(3.9, 2.0)).norm(), 0.0, 1e-9);
}

TEST_F(RunPicturesTest, ReadsALocalizationsFolder) {
  WriteLocalizeRun(localize_);
  const RunRecord run = ReadRun(localize_);
  EXPECT_FALSE(run.slam);
  EXPECT_EQ(run.title,
            "sim/log.clf - localization in sim/world.lines (de, f3), 20 scans - "
            "relation error 0.0114 +- 0.0073 m (sim.relations)");
  EXPECT_EQ(run.error, "0.0114 m relation error");
  ASSERT_TRUE(run.map.walls());
  EXPECT_EQ(run.map.walls()->size(), testing::BoxRoom().size());
  EXPECT_TRUE(run.truth.empty());
  EXPECT_TRUE(run.odometry.empty());
  EXPECT_EQ(WriteRunPictures(run, dir_.path()), std::vector<std::string>{"map.png"});
  EXPECT_TRUE(FindText(ReadPng(dir_ / "map.png"), "walls", kInkColor, 2));
}

TEST_F(RunPicturesTest, AComparisonNamesEachRunByItsFolderAndError) {
  WriteSlamRun(slam_, 30, 2.0);
  WriteSlamRun(dir_ / "other", 25, 5.0);
  const RunRecord run = ReadRun(slam_);
  const RunRecord other = ReadRun(dir_ / "other/");
  const MapPictureContent content = TrajectoryPicture(run, &other);
  std::vector<std::string> labels;
  for (const TrajectoryLayer& layer : content.layers) labels.push_back(layer.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"odometry alone", "ground truth",
                                              (dir_ / "other").string() + " (1.23 cm aligned RMS)",
                                              slam_.string() + " (1.23 cm aligned RMS)"}));
  EXPECT_EQ(content.layers[2].kind, LayerKind::kCompared);
  EXPECT_EQ(content.layers[2].poses.size(), 25u);
  const Image image = DrawMapPicture(run.map, content);
  EXPECT_GT(CountPixels(image, kComparedColor), 500);
  EXPECT_TRUE(FindText(image, content.layers[2].label, kInkColor, 2));
}

TEST_F(RunPicturesTest, AFolderThatLacksAFileIsRefusedNamingIt) {
  ExpectRefused(dir_ / "nowhere", "is not a folder");
  for (const char* file :
       {"report.json", "trajectory.txt", "odometry.txt", "truth.txt", "map.yaml", "map.pgm"}) {
    const fs::path dir = dir_ / file;
    WriteSlamRun(dir, 30, 2.0);
    fs::remove(dir / file);
    ExpectRefused(dir, file);
  }
  WriteLocalizeRun(localize_);
  fs::remove(localize_ / "map.lines");
  ExpectRefused(localize_, "map.lines");
}

TEST_F(RunPicturesTest, AReportOfNeitherKindOrALoopPastThePosesIsRefused) {
  WriteSlamRun(slam_, 30, 2.0);
  WriteFileBytes(slam_ / "report.json", "{\"no_such_field\": 1}");
  ExpectRefused(slam_, "neither a slam nor a localize report");
  WriteSlamRun(slam_, 30, 2.0);
  WriteTrajectoryText(Line(20, 2.0), slam_ / "trajectory.txt");
  ExpectRefused(slam_, "the loop from scan 29 back to 2 lies beyond the 20 poses");
}

}  // namespace
}  // namespace evoslam
