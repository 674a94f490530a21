#include "common/report/slam_outputs.h"

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "common/grid/grid_image.h"
#include "common/grid/map_io.h"
#include "common/image/bitmap_font.h"
#include "common/image/image.h"
#include "common/io/trajectory_io.h"
#include "common/report/map_picture.h"
#include "common/report/pareto_csv.h"
#include "common/report/pareto_testing.h"
#include "common/report/run_pictures.h"
#include "common/report/slam_report.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/methods/slam_methods.h"
#include "common/slam/slam_params.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

constexpr std::size_t kScans = 30;

Dataset SimulatedLog() {
  SimulationOptions options;
  options.max_scans = kScans;
  // Long steps and a strong heading drift, so that odometry parts from the truth visibly.
  options.step = 0.2;
  options.noise.odometry.rotation_bias = 0.05;
  return Simulate(BuiltinWorld("office-boxes"), options);
}

proto::SlamParams Params() {
  proto::SlamParams p;
  p.set_method("rss");
  p.set_log("office-boxes.clf");
  p.set_seed(7);
  SetSlamParam(p, "local.fitness", "eval1");
  SetSlamParam(p, "local.particles", "10");
  SetSlamParam(p, "local.iterations", "30");
  SetSlamParam(p, "map.cell_size_m", "0.05");
  SetSlamParam(p, "global.every_scans", "300");
  SetSlamParam(p, "global.partitions", "8");
  SetSlamParam(p, "global.islands", "2");
  SetSlamParam(p, "global.preset", "mu+lambda-002");
  SetSlamParam(p, "global.generations", "100");
  return p;
}

// A run that found the true poses shifted by `offset`, one loop from scan 25 back to scan 2,
// and applied the global search it triggered.
SlamResult ResultAtTruth(const Dataset& log, const Eigen::Vector2d& offset = {0, 0},
                         double cell_size = 0.05) {
  std::vector<StampedPose> trajectory;
  for (const LaserScan& s : log.scans) {
    const Pose2 pose(s.true_pose->translation() + offset, s.true_pose->theta());
    trajectory.push_back({s.timestamp, pose});
  }
  OccupancyGrid map = OccupancyGridAtPoses(log, trajectory, cell_size);
  SlamResult r{.trajectory = std::move(trajectory),
               .map = std::move(map),
               .loops = {},
               .odometry_stalls = {},
               .seconds = 0.0,
               .evaluations = 0,
               .method_report = {},
               .pareto_fronts = {}};
  const LoopConstraint loop{2, 25, r.trajectory[2].pose.inverse() * r.trajectory[25].pose};
  r.loops.push_back({loop, 0.8, 0.15});
  r.seconds = 1.875;
  r.evaluations = 9700;
  proto::RssRunReport& rss = *r.method_report.mutable_rss();
  rss.set_local_evaluations(9000);
  rss.set_global_evaluations(700);
  rss.mutable_times()->set_local_s(1.0);
  rss.mutable_times()->set_detection_s(0.25);
  rss.mutable_times()->set_global_s(0.5);
  rss.mutable_times()->set_total_s(1.875);
  proto::GlobalSearchRecord& search = *rss.add_global_searches();
  search.set_first(2);
  search.set_last(26);
  search.set_loop(true);
  search.set_applied(true);
  search.set_evaluations(700);
  search.set_seconds(0.5);
  for (double v : {-3.0, 1.5}) search.add_before(v);
  for (double v : {-3.25, 0.0}) search.add_after(v);
  return r;
}

class SlamOutputsTest : public ::testing::Test {
 protected:
  // The files, written into the scratch folder for the readers, and by name.
  std::map<std::string, std::string> Write(const std::vector<proto::ResultFile>& files) {
    std::map<std::string, std::string> by_name;
    for (const proto::ResultFile& f : files) {
      std::ofstream(dir_ / f.name(), std::ios::binary) << f.content();
      by_name[f.name()] = f.content();
    }
    return by_name;
  }

  proto::SlamReport ReadReport() const {
    std::ifstream in(dir_ / "report.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    proto::SlamReport report;
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &report).ok()) << json;
    return report;
  }

  const Dataset log_ = SimulatedLog();
  const SlamResult result_ = ResultAtTruth(log_);
  TempDir dir_;
};

TEST_F(SlamOutputsTest, HandsBackTheFilesItsReportLists) {
  const auto files = SlamOutputs(log_, Params(), result_, std::nullopt, 2);
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(f.name());
  const std::vector<std::string> expected = {
      "trajectory.txt", "trajectory.tum", "odometry.txt",       "truth.txt",   "map.yaml",
      "map.pgm",        "map.png",        "map_trajectory.png", "report.json", "summary.txt"};
  EXPECT_EQ(names, expected);
  Write(files);
  const proto::SlamReport report = ReadReport();
  EXPECT_EQ(std::vector<std::string>(report.outputs().begin(), report.outputs().end()), expected);
}

TEST_F(SlamOutputsTest, WithoutParetoFrontsThereAreNoParetoFiles) {
  ASSERT_TRUE(result_.pareto_fronts.empty());
  for (const auto& f : SlamOutputs(log_, Params(), result_, std::nullopt, 2)) {
    EXPECT_EQ(f.name().find("pareto"), std::string::npos) << f.name();
  }
}

TEST_F(SlamOutputsTest, ParetoFrontsAreWrittenAndListedAfterTheMapPictures) {
  SlamResult result = result_;
  result.pareto_fronts = testing::TwoWindowFronts();
  const auto files = SlamOutputs(log_, Params(), result, std::nullopt, 2);
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(f.name());
  const std::vector<std::string> expected = {"trajectory.txt", "trajectory.tum",     "odometry.txt",
                                             "truth.txt",      "map.yaml",           "map.pgm",
                                             "map.png",        "map_trajectory.png", "pareto.csv",
                                             "pareto.png",     "report.json",        "summary.txt"};
  EXPECT_EQ(names, expected);
  const auto by_name = Write(files);
  const proto::SlamReport report = ReadReport();
  EXPECT_EQ(std::vector<std::string>(report.outputs().begin(), report.outputs().end()), expected);
  EXPECT_EQ(by_name.at("pareto.csv"), ParetoCsv(result.pareto_fronts));
  const Image picture = ReadPng(dir_ / "pareto.png");
  EXPECT_GE(picture.width(), 1000);
  EXPECT_TRUE(FindText(picture, ReadRun(dir_.path()).title, kInkColor, 2)) << "the run's title";
  EXPECT_TRUE(FindText(picture, "occupied cells, relative to start", kInkColor, 2));
  const auto again = SlamOutputs(log_, Params(), result, std::nullopt, 2);
  ASSERT_EQ(again.size(), files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    EXPECT_EQ(again[i].content(), files[i].content()) << files[i].name();
  }
}

TEST_F(SlamOutputsTest, ParetoFrontsThatDoNotFitAreAnError) {
  SlamResult result = result_;
  result.pareto_fronts = testing::TwoWindowFronts();
  result.pareto_fronts[1].chosen = 7;
  EXPECT_THROW(SlamOutputs(log_, Params(), result, std::nullopt, 1), Error);
}

// What the pictures draw besides the estimate: the odometry and the truth at each scan.
TEST_F(SlamOutputsTest, OdometryAndTruthFilesHoldEachScansPoses) {
  Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  const std::vector<StampedPose> odometry = ReadTrajectory(dir_ / "odometry.txt");
  const std::vector<StampedPose> truth = ReadTrajectory(dir_ / "truth.txt");
  ASSERT_EQ(odometry.size(), kScans);
  ASSERT_EQ(truth.size(), kScans);
  for (std::size_t i = 0; i < kScans; ++i) {
    EXPECT_NEAR(odometry[i].timestamp, log_.scans[i].timestamp, 1e-6);
    EXPECT_NEAR((odometry[i].pose.translation() - log_.scans[i].odometry.translation()).norm(), 0,
                1e-6);
    EXPECT_NEAR((truth[i].pose.translation() - log_.scans[i].true_pose->translation()).norm(), 0,
                1e-6);
  }
}

TEST_F(SlamOutputsTest, TrajectoryFilesReadBackAsTheResultStampedWithTheScans) {
  Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  for (const char* name : {"trajectory.txt", "trajectory.tum"}) {
    const std::vector<StampedPose> back = ReadTrajectory(dir_ / name);
    ASSERT_EQ(back.size(), kScans) << name;
    for (std::size_t i = 0; i < kScans; ++i) {
      EXPECT_NEAR(back[i].timestamp, log_.scans[i].timestamp, 1e-6) << name << " " << i;
      EXPECT_NEAR((back[i].pose.translation() - result_.trajectory[i].pose.translation()).norm(),
                  0.0, 1e-6)
          << name << " " << i;
      EXPECT_NEAR(WrapAngle(back[i].pose.theta() - result_.trajectory[i].pose.theta()), 0.0, 1e-6)
          << name << " " << i;
    }
  }
}

TEST_F(SlamOutputsTest, MapIsOccupiedWhereBeamsEndAndFreeWhereTheyPass) {
  Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  const OccupancyGrid map = ReadMapYaml(dir_ / "map.yaml");
  EXPECT_DOUBLE_EQ(map.resolution(), 0.05);
  std::size_t ends = 0, occupied = 0, passes = 0, free = 0;
  for (std::size_t i = 0; i < kScans; ++i) {
    const LaserScan& scan = log_.scans[i];
    const Pose2& pose = result_.trajectory[i].pose;
    for (const Eigen::Vector2d& end : ReturnPoints(scan)) {
      const auto cell = map.WorldToCell(pose * end);
      ASSERT_TRUE(cell) << "every return lies on the map";
      ++ends;
      occupied += map.state(cell->x(), cell->y()) == CellState::kOccupied;
      if (end.norm() < 1.0) continue;
      // Half a metre out along the beam, well clear of the wall it hit.
      const auto near = map.WorldToCell(pose * (0.5 * end.normalized()));
      ++passes;
      free += map.state(near->x(), near->y()) == CellState::kFree;
    }
  }
  ASSERT_GT(ends, 1000u);
  // A cell a return ends in near its edge is crossed by other scans' beams that end in the cell
  // beside it; their misses outweigh its hit in some 7 % of them.
  EXPECT_GT(static_cast<double>(occupied) / ends, 0.9) << occupied << " of " << ends;
  EXPECT_EQ(free, passes);
}

TEST_F(SlamOutputsTest, MapPngShowsTheMapWithItsLegendAndScaleAlone) {
  Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  const Image image = ReadPng(dir_ / "map.png");
  EXPECT_GE(std::max(image.width(), image.height()), 1000);
  EXPECT_GT(CountPixels(image, kOccupiedCellColor), 1000);
  for (const char* label : {"occupied", "free", "unexplored"}) {
    EXPECT_TRUE(FindText(image, label, kInkColor, 2)) << label;
  }
  for (const Rgb color : {kEstimateColor, kTruthColor, kOdometryColor, kLoopColor}) {
    EXPECT_EQ(CountPixels(image, color), 0);
  }
}

TEST_F(SlamOutputsTest, MapTrajectoryShowsEveryTrajectoryAndTheLoops) {
  // Shifted across the straight route, so that the estimate does not hide the truth.
  SlamResult shifted = ResultAtTruth(log_, {0.0, 0.6});
  Write(SlamOutputs(log_, Params(), shifted, std::nullopt, 2));
  const Image image = ReadPng(dir_ / "map_trajectory.png");
  EXPECT_GT(CountPixels(image, kEstimateColor), 100);
  EXPECT_GT(CountPixels(image, kTruthColor), 100);
  EXPECT_GT(CountPixels(image, kOdometryColor), 100);
  EXPECT_GT(CountPixels(image, kLoopColor), 100);
  EXPECT_GT(CountPixels(image, kOccupiedCellColor), 1000) << "the walls";
  for (const char* label :
       {"estimate", "ground truth", "odometry alone", "loop closures (1)", "occupied"}) {
    EXPECT_TRUE(FindText(image, label, kInkColor, 2)) << label;
  }

  shifted.loops.clear();
  Write(SlamOutputs(log_, Params(), shifted, std::nullopt, 2));
  const Image without = ReadPng(dir_ / "map_trajectory.png");
  EXPECT_TRUE(FindText(without, "loop closures (0)", kInkColor, 2));
  EXPECT_LT(CountPixels(without, kLoopColor), CountPixels(image, kLoopColor) - 50)
      << "the legend's mark alone";
}

// Both pictures are 1,000 pixels or more on their long side even for a map of coarse cells,
// which has fewer cells than that.
TEST_F(SlamOutputsTest, PicturesHaveAThousandPixelsOnTheLongSideWhateverTheCells) {
  const SlamResult coarse = ResultAtTruth(log_, {0, 0}, 0.5);
  ASSERT_LT(std::max(coarse.map.width(), coarse.map.height()), 100);
  Write(SlamOutputs(log_, Params(), coarse, std::nullopt, 1));
  for (const char* name : {"map.png", "map_trajectory.png"}) {
    const Image image = ReadPng(dir_ / name);
    EXPECT_GE(std::max(image.width(), image.height()), 1000) << name;
  }
}

TEST_F(SlamOutputsTest, TheTitleNamesTheLogTheMethodAndTheError) {
  Write(SlamOutputs(log_, Params(), result_, std::nullopt, 1));
  const std::string title =
      "office-boxes.clf - SLAM (rss), 30 scans - aligned RMS error 0.00 cm against ground truth";
  for (const char* name : {"map.png", "map_trajectory.png"}) {
    EXPECT_TRUE(FindText(ReadPng(dir_ / name), title, kInkColor, 2)) << name;
  }
  Dataset log = log_;
  for (LaserScan& s : log.scans) s.true_pose.reset();
  Write(SlamOutputs(log, Params(), result_, std::nullopt, 1));
  EXPECT_TRUE(FindText(ReadPng(dir_ / "map_trajectory.png"),
                       "office-boxes.clf - SLAM (rss), 30 scans", kInkColor, 2));
  EXPECT_FALSE(FindText(ReadPng(dir_ / "map_trajectory.png"), "error", kInkColor, 2));
}

// The pictures are drawn from the other files, so that drawing them again from the folder, as
// `evoslam plot` does, gives the same bytes.
TEST_F(SlamOutputsTest, ThePicturesDrawnAgainFromTheFolderAreTheSameBytes) {
  const auto files = Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  const TempDir again;
  EXPECT_EQ(WriteRunPictures(ReadRun(dir_.path()), again.path()),
            (std::vector<std::string>{"map.png", "map_trajectory.png"}));
  for (const char* name : {"map.png", "map_trajectory.png"}) {
    std::ifstream in(again / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(bytes == files.at(name)) << name;
  }
}

TEST_F(SlamOutputsTest, ReportJsonHoldsTheRunAndItsErrors) {
  Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  const proto::SlamReport r = ReadReport();
  // Every setting as it ran: those given, and the defaults of the rest.
  EXPECT_EQ(r.params().SerializeAsString(), CompleteSlamParams(Params()).SerializeAsString());
  EXPECT_EQ(r.params().seed(), 7u);
  EXPECT_EQ(r.params().rss().global().partitions(), 8u);
  EXPECT_TRUE(r.params().rss().loops().has_min_match_score());
  EXPECT_EQ(r.scans(), kScans);
  EXPECT_EQ(r.evaluations(), 9700u);
  EXPECT_DOUBLE_EQ(r.seconds(), 1.875);
  EXPECT_EQ(r.rss().local_evaluations(), 9000u);
  EXPECT_EQ(r.rss().global_evaluations(), 700u);
  EXPECT_DOUBLE_EQ(r.rss().times().detection_s(), 0.25);
  EXPECT_DOUBLE_EQ(r.scans_per_second(), kScans / 1.875);
  EXPECT_EQ(r.threads(), 2u);
  EXPECT_NEAR(r.log_duration_s(), (kScans - 1) * SimulationOptions{}.scan_interval, 1e-6);

  ASSERT_EQ(r.loops_size(), 1);
  EXPECT_EQ(r.loops(0).earlier(), 2u);
  EXPECT_EQ(r.loops(0).later(), 25u);
  const Pose2& relative = result_.loops[0].constraint.relative;
  ASSERT_EQ(r.loops(0).relative_size(), 3);
  EXPECT_DOUBLE_EQ(r.loops(0).relative(0), relative.x());
  EXPECT_DOUBLE_EQ(r.loops(0).relative(1), relative.y());
  EXPECT_DOUBLE_EQ(r.loops(0).relative(2), relative.theta());
  EXPECT_DOUBLE_EQ(r.loops(0).score(), 0.8);
  EXPECT_DOUBLE_EQ(r.loops(0).distinctness(), 0.15);
  ASSERT_EQ(r.rss().global_searches_size(), 1);
  const auto& g = r.rss().global_searches(0);
  EXPECT_EQ(g.first(), 2u);
  EXPECT_EQ(g.last(), 26u);
  EXPECT_TRUE(g.loop());
  EXPECT_TRUE(g.applied());
  EXPECT_EQ(g.evaluations(), 700u);
  EXPECT_EQ(std::vector<double>(g.before().begin(), g.before().end()),
            std::vector<double>({-3.0, 1.5}));
  EXPECT_EQ(std::vector<double>(g.after().begin(), g.after().end()),
            std::vector<double>({-3.25, 0.0}));

  // The estimate is the truth; odometry drifts from it.
  EXPECT_EQ(r.absolute_errors().poses(), kScans);
  EXPECT_NEAR(r.absolute_errors().max_translation_m(), 0.0, 1e-12);
  EXPECT_EQ(r.odometry_absolute_errors().poses(), kScans);
  EXPECT_GT(r.odometry_absolute_errors().rms_translation_m(), 1e-3);
  EXPECT_EQ(r.relation_errors().source(), "ground truth, consecutive scans");
  EXPECT_EQ(r.relation_errors().relations(), kScans - 1);
  EXPECT_NEAR(r.relation_errors().translation_mean_m(), 0.0, 1e-9);
  EXPECT_EQ(r.odometry_relation_errors().relations(), kScans - 1);
  EXPECT_GT(r.odometry_relation_errors().translation_mean_m(), 1e-4);
}

TEST_F(SlamOutputsTest, RelationsGivenAreTheOnesMeasured) {
  // Scan 10 seen from scan 0 as the truth has it, but 10 cm further along.
  const Pose2 truth = *log_.scans[0].true_pose;
  const Pose2 later = *log_.scans[10].true_pose;
  const NamedRelations relations{"office.relations",
                                 {{log_.scans[0].timestamp, log_.scans[10].timestamp,
                                   truth.inverse() * later * Pose2(0.1, 0, 0)}}};
  const proto::SlamReport r = MakeSlamReport(log_, Params(), result_, relations, 1);
  EXPECT_EQ(r.relation_errors().source(), "office.relations");
  EXPECT_EQ(r.relation_errors().relations(), 1u);
  EXPECT_NEAR(r.relation_errors().translation_mean_m(), 0.1, 1e-9);
  EXPECT_EQ(r.odometry_relation_errors().source(), "office.relations");
  EXPECT_EQ(r.odometry_relation_errors().relations(), 1u);
}

TEST_F(SlamOutputsTest, ALogWithoutTruthHasNoErrorsButTheSameFiles) {
  Dataset log = log_;
  for (LaserScan& s : log.scans) s.true_pose.reset();
  const auto files = SlamOutputs(log, Params(), result_, std::nullopt, 1);
  EXPECT_EQ(files.size(), 9u) << "no truth.txt";
  Write(files);
  const proto::SlamReport r = ReadReport();
  EXPECT_FALSE(r.has_absolute_errors());
  EXPECT_FALSE(r.has_odometry_absolute_errors());
  EXPECT_FALSE(r.has_relation_errors());
  EXPECT_FALSE(r.has_odometry_relation_errors());
}

TEST_F(SlamOutputsTest, TheSameResultGivesTheSameBytes) {
  const auto first = SlamOutputs(log_, Params(), result_, std::nullopt, 2);
  const auto second = SlamOutputs(log_, Params(), result_, std::nullopt, 2);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].content(), second[i].content()) << first[i].name();
  }
}

TEST_F(SlamOutputsTest, SummarySaysWhatRanWhatItFoundAndHowWell) {
  const auto files = Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2));
  const std::string s = files.at("summary.txt");
  EXPECT_EQ(s, FormatSlamSummary(ReadReport()));
  for (const char* line : {
           "SLAM (rss) over 30 scans of office-boxes.clf, 5.80 s of log",
           "local search: PSO of 10 particles x 30 iterations on eval1, map cells 0.05 m, ties to "
           "odometry, a second swarm at odometry's heading, odometry where the scan fixes nothing, "
           "refined below a cell",
           "global search: on a loop or every 300 steps, 8 partitions, 1 return in 2 scored, 2 "
           "islands of mu+lambda-002 x 100 generations",
           "time 1.88 s (16.00 scans/s, 2 threads)",
           "phases: local search 1.00 s, loop detection 0.25 s, global search 0.50 s",
           "fitness evaluations: 9000 local, 700 global",
           "loops found: 1 (scan 25 back to 2, score 0.80, distinctness 0.15)",
           "global searches: 1, 1 applied",
           "RMS error vs ground truth: x 0.00 cm, y 0.00 cm, heading 0.00 deg (max 0.00 cm); "
           "aligned: 0.00 cm; aligned and scaled (x1.0000): 0.00 cm",
           "relative error (ground truth, consecutive scans, 29 relations): 0.0000 +- 0.0000 m",
       }) {
    EXPECT_NE(s.find(line), std::string::npos) << line << "\n" << s;
  }
  EXPECT_EQ(s.find("odometry alone: x 0.00 cm"), std::string::npos) << "odometry drifts\n" << s;
}

TEST_F(SlamOutputsTest, TheReportAndSummaryNameWhereTheOdometryStalled) {
  SlamResult result = ResultAtTruth(log_);
  result.odometry_stalls = {
      {.first = 4, .last = 7, .catch_up = Pose2(0.8, 0.1, -0.5)},
      {.first = 12, .last = 12, .catch_up = Pose2(0.0, 0.0, 1.5)},
      {.first = 20, .last = 21, .catch_up = Pose2(0.6, 0.0, 0.1), .heading_held = false}};
  const std::string s =
      Write(SlamOutputs(log_, Params(), result, std::nullopt, 2)).at("summary.txt");
  EXPECT_NE(s.find("odometry stalled while the robot moved, filled in by time: scans 4 to 7 "
                   "(then 0.81 m and -28.6 deg), 12 to 12 (then 0.00 m and 85.9 deg), 20 to 21 "
                   "(position only, then 0.60 m and 5.7 deg)\n"),
            std::string::npos)
      << s;
  const proto::SlamReport r = ReadReport();
  ASSERT_EQ(r.odometry_stalls_size(), 3);
  EXPECT_EQ(r.odometry_stalls(0).first(), 4u);
  EXPECT_EQ(r.odometry_stalls(0).last(), 7u);
  EXPECT_DOUBLE_EQ(r.odometry_stalls(0).catch_up_m(), std::hypot(0.8, 0.1));
  EXPECT_DOUBLE_EQ(r.odometry_stalls(1).catch_up_rad(), 1.5);
  EXPECT_FALSE(r.odometry_stalls(1).position_only());
  EXPECT_TRUE(r.odometry_stalls(2).position_only());
  // Without stalls the summary says nothing of them.
  EXPECT_EQ(Write(SlamOutputs(log_, Params(), result_, std::nullopt, 2))
                .at("summary.txt")
                .find("stalled"),
            std::string::npos);
}

TEST_F(SlamOutputsTest, SummarySaysWhenTheSeenSpacesEdgeIsLeftFree) {
  proto::SlamParams params = Params();
  params.mutable_rss()->mutable_local()->set_free_frontier(true);
  const std::string s =
      Write(SlamOutputs(log_, params, result_, std::nullopt, 2)).at("summary.txt");
  EXPECT_NE(s.find("odometry where the scan fixes nothing, the seen space's edge free, refined "
                   "below a cell"),
            std::string::npos)
      << s;
}

// The map written is the result's, at its resolution.
TEST_F(SlamOutputsTest, TheMapWrittenIsTheResults) {
  const SlamResult coarse = ResultAtTruth(log_, {0, 0}, 0.1);
  Write(SlamOutputs(log_, Params(), coarse, std::nullopt, 1));
  EXPECT_DOUBLE_EQ(ReadReport().map_resolution_m(), 0.1);
  const OccupancyGrid map = ReadMapYaml(dir_ / "map.yaml");
  EXPECT_DOUBLE_EQ(map.resolution(), 0.1);
  EXPECT_EQ(map.width(), coarse.map.width());
  EXPECT_EQ(map.height(), coarse.map.height());
}

TEST_F(SlamOutputsTest, AResultThatDoesNotFitTheLogIsAnError) {
  Dataset shorter = log_;
  shorter.scans.pop_back();
  EXPECT_THROW(SlamOutputs(shorter, Params(), result_, std::nullopt, 1), Error);
  SlamResult bad_loop = result_;
  bad_loop.loops[0].constraint.later = kScans;
  EXPECT_THROW(SlamOutputs(log_, Params(), bad_loop, std::nullopt, 1), Error);
  SlamResult empty = result_;
  empty.trajectory.clear();
  empty.loops.clear();
  EXPECT_THROW(SlamOutputs(log_, Params(), empty, std::nullopt, 1), Error);
}

}  // namespace
}  // namespace evoslam
