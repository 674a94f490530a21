// The evoslam command line end to end: outputs, exit codes and error messages.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/image/bitmap_font.h"
#include "common/image/image.h"
#include "common/io/trajectory_io.h"
#include "common/report/map_picture.h"
#include "common/util/temp_dir.h"
#include "evoslam/slam.pb.h"
#include "tests/cli_testing.h"

namespace {

namespace fs = std::filesystem;

using evoslam::testing::RunCli;
using evoslam::testing::RunCommand;
using Result = evoslam::testing::CommandResult;

// bench/seed_sweep.sh with this build's evoslam.
Result RunSweep(const std::string& args) {
  return RunCommand(std::string(EVOSLAM_SEED_SWEEP) + " --evoslam " + EVOSLAM_CLI + " " + args);
}

// bench/compare_sweeps.sh on two sweeps.
Result RunCompare(const std::string& before, const std::string& after) {
  return RunCommand(std::string(EVOSLAM_COMPARE_SWEEPS) + " " + before + " " + after);
}

class CliTest : public ::testing::Test {
 protected:
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  evoslam::TempDir dir_;
};

TEST_F(CliTest, SimulateThenLocalizeWritesEveryOutput) {
  const Result sim =
      RunCli("simulate --world s-corridor --noise-uniform 0.2 --max-scans 40 --seed 3 --out " +
             Path("sim"));
  ASSERT_EQ(sim.status, 0) << sim.output;
  for (const char* f : {"log.clf", "world.lines", "truth.txt"})
    EXPECT_TRUE(fs::exists(dir_ / "sim" / f)) << f;

  const Result loc = RunCli("localize --map " + Path("sim/world.lines") + " --log " +
                            Path("sim/log.clf") + " --seed 3 --out " + Path("run"));
  ASSERT_EQ(loc.status, 0) << loc.output;
  for (const char* f :
       {"trajectory.txt", "trajectory.tum", "report.json", "summary.txt", "map.png"}) {
    EXPECT_TRUE(fs::exists(dir_ / "run" / f)) << f;
  }
  EXPECT_NE(loc.output.find("RMS error vs ground truth"), std::string::npos) << loc.output;
  const auto trajectory = evoslam::ReadTrajectory(dir_ / "run" / "trajectory.txt");
  EXPECT_EQ(trajectory.size(), 40u);
  std::ifstream report(dir_ / "run" / "report.json");
  std::stringstream json;
  json << report.rdbuf();
  EXPECT_NE(json.str().find("\"absolute_errors\""), std::string::npos);
  EXPECT_NE(json.str().find("\"scans\": 40"), std::string::npos) << json.str();

  // eval agrees the trajectory is accurate against the log's ground truth.
  const Result eval =
      RunCli("eval " + Path("run/trajectory.txt") + " --truth " + Path("sim/log.clf"));
  ASSERT_EQ(eval.status, 0) << eval.output;
  EXPECT_NE(eval.output.find("absolute: 40 poses"), std::string::npos) << eval.output;
  EXPECT_NE(eval.output.find("by a rigid motion and a scale of "), std::string::npos)
      << eval.output;

  // Same seed, same trajectory, byte for byte.
  ASSERT_EQ(RunCli("localize --map " + Path("sim/world.lines") + " --log " + Path("sim/log.clf") +
                   " --seed 3 --threads 1 --out " + Path("again"))
                .status,
            0);
  std::ifstream a(dir_ / "run" / "trajectory.txt"), b(dir_ / "again" / "trajectory.txt");
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  EXPECT_EQ(sa.str(), sb.str());

  // F2's tolerance flags reach the job and its report.
  const Result f2 = RunCli("localize --map " + Path("sim/world.lines") + " --log " +
                           Path("sim/log.clf") + " --fitness f2 --f2-base 0.05 --f2-slope 0.002" +
                           " --max-scans 5 --out " + Path("f2"));
  ASSERT_EQ(f2.status, 0) << f2.output;
  EXPECT_NE(f2.output.find("f2 (within 0.050 m + 0.0020 x the two ranges)"), std::string::npos)
      << f2.output;
  const Result capped =
      RunCli("localize --map " + Path("sim/world.lines") + " --log " + Path("sim/log.clf") +
             " --f3-cap 0.4 --max-scans 5 --out " + Path("capped"));
  ASSERT_EQ(capped.status, 0) << capped.output;
  EXPECT_NE(capped.output.find("f3 (each beam's difference capped at 0.400 m)"), std::string::npos)
      << capped.output;
}

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A preset sets the algorithm and its settings; an option given as well overrides just itself.
TEST_F(CliTest, PresetsSetTheAlgorithmAndOptionsOverrideThem) {
  ASSERT_EQ(
      RunCli("simulate --world s-corridor --max-scans 5 --seed 1 --out " + Path("sim")).status, 0);
  const std::string localize =
      "localize --map " + Path("sim/world.lines") + " --log " + Path("sim/log.clf");
  const Result plain = RunCli(localize + " --preset pso-003 --out " + Path("a"));
  ASSERT_EQ(plain.status, 0) << plain.output;
  const std::string a = ReadAll(dir_ / "a" / "report.json");
  EXPECT_NE(a.find("\"particles\": 50"), std::string::npos) << a;
  EXPECT_NE(a.find("\"preset\": \"pso-003\""), std::string::npos) << a;
  const Result overridden =
      RunCli(localize + " --preset pso-003 --population 12 --out " + Path("b"));
  ASSERT_EQ(overridden.status, 0) << overridden.output;
  const std::string b = ReadAll(dir_ / "b" / "report.json");
  EXPECT_NE(b.find("\"particles\": 12"), std::string::npos) << b;
  EXPECT_NE(b.find("\"optimizer\": \"pso\""), std::string::npos) << b;
}

TEST_F(CliTest, KeygenWritesAPairAndNeverOverwritesOneByAccident) {
  const Result first = RunCli("keygen --name worker1 --out " + Path("keys"));
  ASSERT_EQ(first.status, 0) << first.output;
  const std::string public_key = ReadAll(dir_ / "keys" / "worker1.pub");
  EXPECT_EQ(public_key.size(), 41u);  // 40 Z85 characters and a newline
  EXPECT_NE(first.output.find(public_key.substr(0, 40)), std::string::npos) << first.output;
  EXPECT_EQ(ReadAll(dir_ / "keys" / "worker1.key").size(), 41u);

  const Result again = RunCli("keygen --name worker1 --out " + Path("keys"));
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.output.find("already exists"), std::string::npos) << again.output;
  EXPECT_EQ(ReadAll(dir_ / "keys" / "worker1.pub"), public_key);
  ASSERT_EQ(RunCli("keygen --force --name worker1 --out " + Path("keys")).status, 0);
  EXPECT_NE(ReadAll(dir_ / "keys" / "worker1.pub"), public_key);
  EXPECT_EQ(RunCli("keygen --out " + Path("keys")).status, 2);  // --name is required
}

TEST_F(CliTest, MissingFileIsAClearError) {
  const Result r = RunCli("info " + Path("nope.clf"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("nope.clf"), std::string::npos) << r.output;
}

TEST_F(CliTest, MalformedLogNamesFileAndLine) {
  std::ofstream(Path("bad.clf"))
      << "# header\nODOM 0 0 0 0 0 0 1.0 nohost 0\nFLASER 3 1.0 2.0 x 0 0 0 0 0 0 1.0 nohost 0\n"
      << "FLASER 3 1.0 2.0 3.0 0 0 0 0 0 0 2.0 nohost 0\n";
  const Result r = RunCli("info " + Path("bad.clf"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("bad.clf:3"), std::string::npos) << r.output;
  const Result lenient = RunCli("info --lenient " + Path("bad.clf"));
  EXPECT_EQ(lenient.status, 0) << lenient.output;
  EXPECT_NE(lenient.output.find("skipped 1"), std::string::npos) << lenient.output;
}

// A map_server map written by one run is a map for the next, wherever its YAML lives: the
// job carries the YAML and its image to the service, which puts them side by side again.
TEST_F(CliTest, AGridWrittenByOneRunIsTheMapOfTheNext) {
  ASSERT_EQ(
      RunCli("simulate --world s-corridor --max-scans 12 --seed 2 --out " + Path("sim")).status, 0);
  const std::string log = " --log " + Path("sim/log.clf") + " --max-scans 12";
  const Result built =
      RunCli("localize --map-from-log " + Path("sim/log.clf") + log + " --out " + Path("built"));
  ASSERT_EQ(built.status, 0) << built.output;
  fs::create_directories(Path("maps/lab"));
  fs::copy_file(Path("built/map.yaml"), Path("maps/lab/map.yaml"));
  fs::copy_file(Path("built/map.pgm"), Path("maps/lab/map.pgm"));
  const Result reused =
      RunCli("localize --map " + Path("maps/lab/map.yaml") + log + " --out " + Path("reused"));
  ASSERT_EQ(reused.status, 0) << reused.output;
  std::ifstream a(Path("built/trajectory.txt")), b(Path("reused/trajectory.txt"));
  const std::string built_trajectory((std::istreambuf_iterator<char>(a)), {});
  const std::string reused_trajectory((std::istreambuf_iterator<char>(b)), {});
  EXPECT_FALSE(built_trajectory.empty());
  EXPECT_EQ(built_trajectory, reused_trajectory);
}

// A bad log found by the service is named as the user named it, with its line.
TEST_F(CliTest, AMalformedLogFailsTheJobNamingFileAndLine) {
  ASSERT_EQ(
      RunCli("simulate --world s-corridor --max-scans 5 --seed 2 --out " + Path("sim")).status, 0);
  std::ofstream(Path("broken.clf"))
      << "# header\nODOM 0 0 0 0 0 0 1.0 nohost 0\nFLASER 3 1.0 2.0 x 0 0 0 0 0 0 1.0 nohost 0\n";
  const Result r = RunCli("localize --map " + Path("sim/world.lines") + " --log " +
                          Path("broken.clf") + " --out " + Path("o"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(Path("broken.clf") + ":3:"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("evoslam-coordinator"), std::string::npos) << r.output;
}

// A refused command line exits with 2 and says which flag, before any file is touched (m and l
// do not exist); bad files exit with 1.
TEST_F(CliTest, BadFlagsAreRefused) {
  const std::string localize = "localize --map m --log l --out " + Path("o");
  const Result optimizer = RunCli(localize + " --optimizer simplex");
  EXPECT_EQ(optimizer.status, 2);
  EXPECT_NE(optimizer.output.find("--optimizer"), std::string::npos) << optimizer.output;
  EXPECT_EQ(RunCli(localize + " --CR 1.5").status, 2);
  const Result f2_base = RunCli(localize + " --f2-base -0.01");
  EXPECT_EQ(f2_base.status, 2);
  EXPECT_NE(f2_base.output.find("--f2-base"), std::string::npos) << f2_base.output;
  const Result f3_cap = RunCli(localize + " --f3-cap -1");
  EXPECT_EQ(f3_cap.status, 2);
  EXPECT_NE(f3_cap.output.find("--f3-cap"), std::string::npos) << f3_cap.output;
  EXPECT_EQ(RunCli(localize + " --bogus").status, 2);
  const Result strategy = RunCli(localize + " --strategy rand3exp");
  EXPECT_EQ(strategy.status, 2);
  EXPECT_NE(strategy.output.find("rand3exp"), std::string::npos) << strategy.output;
  const Result start = RunCli(localize + " --start 1,2");
  EXPECT_EQ(start.status, 2);
  EXPECT_NE(start.output.find("--start"), std::string::npos) << start.output;
  EXPECT_EQ(RunCli(localize + " --map-from-log l2").status, 2);
  EXPECT_EQ(RunCli(localize + " --optimizer de --population 3").status, 2);
  EXPECT_EQ(RunCli(localize + " --preset de-999").status, 2);
  const Result migrants = RunCli(localize + " --optimizer island --population 10 --migrants 10");
  EXPECT_EQ(migrants.status, 2);
  EXPECT_NE(migrants.output.find("migrants"), std::string::npos) << migrants.output;
  EXPECT_EQ(RunCli(localize + " --optimizer island --topology torus").status, 2);
  EXPECT_EQ(RunCli("eval " + Path("t.txt")).status, 2);
  EXPECT_EQ(RunCli("simulate --world atlantis --out " + Path("o")).status, 2);
  EXPECT_EQ(RunCli("simulate --world s-corridor --world-file w --out " + Path("o")).status, 2);
  EXPECT_EQ(RunCli("frobnicate").status, 2);
  EXPECT_FALSE(fs::exists(dir_ / "o"));
  EXPECT_EQ(RunCli(localize).status, 1);  // a valid command line, but no such files
  // An endpoint ZeroMQ refuses is named, not an internal error.
  const Result endpoint = RunCli("jobs --coordinator garbage");
  EXPECT_EQ(endpoint.status, 1) << endpoint.output;
  EXPECT_NE(endpoint.output.find("cannot connect to the coordinator at garbage"), std::string::npos)
      << endpoint.output;
  EXPECT_EQ(RunCli("--help").status, 0);
}

// --route drives the given waypoints instead of the world's route; a bad route file is named.
TEST_F(CliTest, SimulateDrivesTheGivenRoute) {
  std::ofstream(dir_ / "l.route") << "# an L\n2 2\n6 2\n6 4 # end\n";
  const Result sim = RunCli("simulate --world empty-room --route " + Path("l.route") +
                            " --seed 1 --out " + Path("sim"));
  ASSERT_EQ(sim.status, 0) << sim.output;
  const auto truth = evoslam::ReadTrajectory(dir_ / "sim" / "truth.txt");
  ASSERT_GE(truth.size(), 2u);
  EXPECT_NEAR(truth.front().pose.translation().x(), 2.0, 1e-9);
  EXPECT_NEAR(truth.front().pose.translation().y(), 2.0, 1e-9);
  EXPECT_NEAR(truth.back().pose.translation().x(), 6.0, 1e-9);
  EXPECT_NEAR(truth.back().pose.translation().y(), 4.0, 1e-9);
  for (const auto& p : truth) {
    EXPECT_GE(p.pose.translation().x(), 2.0 - 1e-9);
    EXPECT_LE(p.pose.translation().y(), 4.0 + 1e-9);
  }

  std::ofstream(dir_ / "bad.route") << "2 2\n6 two\n";
  const Result bad =
      RunCli("simulate --world empty-room --route " + Path("bad.route") + " --out " + Path("o"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.output.find(Path("bad.route") + ":2: y is \"two\""), std::string::npos)
      << bad.output;
  std::ofstream(dir_ / "wall.route") << "2 2\n9 2\n";
  const Result wall =
      RunCli("simulate --world empty-room --route " + Path("wall.route") + " --out " + Path("o"));
  EXPECT_EQ(wall.status, 1);
  EXPECT_NE(wall.output.find("must keep 0.5 m"), std::string::npos) << wall.output;
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

// slam refuses a bad command line with 2, naming the flag, before it simulates or reads anything.
TEST_F(CliTest, SlamRefusesBadFlags) {
  const std::string slam = "slam --out " + Path("o");
  for (const auto& [flag, shown] : std::vector<std::pair<std::string, std::string>>{
           {"--method icp", "--method"},
           {"--local-fitness eval3", "eval3"},
           {"--local-population -3", "--local-population"},
           {"--resolution -0.05", "--resolution"},
           {"--loop-radius 0", "--loop-radius"},
           {"--generations 0", "--generations"},
           {"--seed -1", "--seed"},
           {"--world atlantis", "atlantis"},
           {"--world s-corridor --log l", "--log"},
           {"--preset de-999", "de-999"},
           {"--param bogus=1", "bogus"},
           {"--param global.occupied_pose_weight=abc", "abc"},
           {"--param global.spread_x=0.1,0.2", "global.spread_x"},
           {"--param log=x", "--log"},
           {"--param local", "NAME=VALUE"},
           {"--min-match-score 0", "match"},
           {"--param local.odometry_below_information=1", "local.odometry_below_information"},
           {"--param rss.local.odometry_weight=-0.1", "local.odometry_weight"},
           {"--config " + Path("none.txt"), "none.txt"},
           {"--detach", "--coordinator"},
       }) {
    const Result r = RunCli(slam + " " + flag);
    EXPECT_EQ(r.status, 2) << flag << ": " << r.output;
    EXPECT_NE(r.output.find(shown), std::string::npos) << flag << ": " << r.output;
  }
  EXPECT_EQ(RunCli("slam --world s-corridor").status, 2);  // the simulated log needs --out
  EXPECT_FALSE(fs::exists(dir_ / "o"));
  const Result missing = RunCli("slam --log " + Path("nope.clf") + " --out " + Path("o"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.output.find("nope.clf"), std::string::npos) << missing.output;
}

// Each flag sets its parameter and leaves the others at their defaults; --param reaches the rest.
TEST_F(CliTest, SlamFlagsSetTheirParameters) {
  const Result defaults = RunCli("slam --print-params");
  ASSERT_EQ(defaults.status, 0) << defaults.output;
  EXPECT_NE(defaults.output.find("method: \"rss\""), std::string::npos) << defaults.output;
  EXPECT_NE(defaults.output.find("enabled: true"), std::string::npos) << defaults.output;
  EXPECT_NE(defaults.output.find("particles: 10\n"), std::string::npos) << defaults.output;
  EXPECT_EQ(defaults.output.find("log:"), std::string::npos) << defaults.output;
  const Result set = RunCli(
      "slam --print-params --log run.clf --local-population 12 --local-fitness eval2 --local-only "
      "--global-every 0 --partitions 4 --generations 7 --islands 3 --preset de-000 "
      "--max-stretch 90 --loop-radius 1.5 --min-match-score 0.7 --resolution 0.1 "
      "--local-iterations 20 --max-scans 50 --seed 9 --lenient "
      "--param global.spread_theta=0.25 --param rss.global.loop_miss_weight=0.25");
  ASSERT_EQ(set.status, 0) << set.output;
  for (const char* line : {"particles: 12",
                           "fitness: \"eval2\"",
                           "enabled: false",
                           "every_scans: 0",
                           "partitions: 4",
                           "generations: 7",
                           "islands: 3",
                           "preset: \"de-000\"",
                           "max_stretch_scans: 90",
                           "revisit_radius_m: 1.5",
                           "min_match_score: 0.7",
                           "cell_size_m: 0.1",
                           "iterations: 20",
                           "max_scans: 50",
                           "seed: 9",
                           "lenient: true",
                           "spread_theta: 0.25",
                           "spread_y: 0.3",
                           "loop_miss_weight: 0.25",
                           "occupied_pose_weight: 0.5"}) {
    EXPECT_NE(set.output.find(std::string(line) + "\n"), std::string::npos) << line << "\n"
                                                                            << set.output;
  }
}

// Another method's flags set its parameters, in whatever order they come with --method; a flag of
// a method other than the run's is refused.
TEST_F(CliTest, TheImmuneMethodsFlagsSetItsParameters) {
  const Result set = RunCli(
      "slam --print-params --variant moea --method immune --window-segments 8 --population 20 "
      "--max-generations 40 --encoding continuous --evidence-cell 0.1 --param scan_stride=2");
  ASSERT_EQ(set.status, 0) << set.output;
  for (const char* line :
       {"method: \"immune\"", "variant: \"moea\"", "window_segments: 8", "population: 20",
        "generations: 40", "encoding: \"continuous\"", "cell_size_m: 0.1", "scan_stride: 2"}) {
    EXPECT_NE(set.output.find(std::string(line) + "\n"), std::string::npos) << line << "\n"
                                                                            << set.output;
  }
  EXPECT_EQ(set.output.find("rss {"), std::string::npos) << set.output;
  const Result mixed = RunCli("slam --print-params --variant moea");
  EXPECT_EQ(mixed.status, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("parameters of method immune"), std::string::npos) << mixed.output;
  const Result bad = RunCli("slam --print-params --method immune --variant nsga2");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("nsga2"), std::string::npos) << bad.output;
}

// What --print-params writes, --config reads back to the same run; flags and --param apply on
// top of the file.
TEST_F(CliTest, SlamConfigReadsBackWhatPrintParamsWrites) {
  const Result printed = RunCli("slam --print-params --seed 4 --param local.particles=12");
  ASSERT_EQ(printed.status, 0) << printed.output;
  {
    std::ofstream config(dir_ / "p.txt");
    config << printed.output;
  }
  const std::string drive = "slam --world s-corridor --max-scans 60 --generations 5";
  const Result plain = RunCli(drive + " --seed 4 --local-population 12 --out " + Path("plain"));
  ASSERT_EQ(plain.status, 0) << plain.output;
  const Result configured = RunCli(drive + " --config " + Path("p.txt") + " --out " + Path("cfg"));
  ASSERT_EQ(configured.status, 0) << configured.output;
  EXPECT_EQ(ReadAll(dir_ / "cfg" / "trajectory.txt"), ReadAll(dir_ / "plain" / "trajectory.txt"));

  const Result reprinted = RunCli("slam --print-params --config " + Path("p.txt"));
  EXPECT_EQ(reprinted.output, printed.output);
  const Result overridden = RunCli("slam --print-params --config " + Path("p.txt") +
                                   " --seed 5 --param local.particles=13");
  EXPECT_NE(overridden.output.find("seed: 5\n"), std::string::npos) << overridden.output;
  EXPECT_NE(overridden.output.find("particles: 13\n"), std::string::npos) << overridden.output;

  {
    std::ofstream bad(dir_ / "bad.txt");
    bad << "seed: 3\nrss {\n  local { particles: lots }\n}\n";
  }
  const Result refused = RunCli("slam --print-params --config " + Path("bad.txt"));
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("bad.txt: line 3"), std::string::npos) << refused.output;
}

// A method that does not exist is refused with the list of those that do.
TEST_F(CliTest, SlamRefusesAnUnknownMethodListingTheKnownOnes) {
  for (const std::string how : {"--method gslam", "--param method=gslam"}) {
    const Result r = RunCli("slam --print-params " + how);
    EXPECT_EQ(r.status, 2) << how << ": " << r.output;
    EXPECT_NE(r.output.find("rss"), std::string::npos) << how << ": " << r.output;
  }
}

evoslam::proto::SlamReport ReadSlamReport(const fs::path& path) {
  evoslam::proto::SlamReport report;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(ReadAll(path), &report).ok()) << path;
  return report;
}

// The main job: SLAM on a simulated drive, every output written, errors against the truth the
// simulation logged below odometry's; --local-only runs no global search.
// The demo's run, `slam` with no input, gives the trajectory it gave when the file was written,
// to the last bit: a change that alters a result must say so by changing the file
// (`evoslam slam --out DIR`, then copy DIR/trajectory.txt to tests/data/demo-trajectory.txt).
// Its picture explains itself: a title, a legend naming each line, the map filling the picture
// though odometry alone drifts metres off it, and the truth showing beside the estimate that
// follows it to a centimetre.
TEST_F(CliTest, TheDemosTrajectoryIsPinnedToTheBitAndItsPictureExplainsItself) {
#ifdef EVOSLAM_SANITIZED
  GTEST_SKIP() << "the whole demo takes minutes under the sanitizers; the Release pass pins it";
#endif
  const Result r = RunCli("slam --out " + Path("demo"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(ReadAll(dir_ / "demo" / "trajectory.txt") == ReadAll(EVOSLAM_DEMO_TRAJECTORY))
      << "the demo's trajectory differs from " << EVOSLAM_DEMO_TRAJECTORY;

  const evoslam::Image image = evoslam::ReadPng(dir_ / "demo" / "map_trajectory.png");
  EXPECT_GE(std::max(image.width(), image.height()), 1000);
  // The title, word by word: the scratch folder's path may be long enough to wrap it.
  for (const char* word : {"SLAM", "(rss),", "1823", "aligned"}) {
    EXPECT_TRUE(evoslam::FindText(image, word, evoslam::kInkColor, 2)) << word;
  }
  for (const char* label : {"estimate", "ground truth", "odometry alone", "loop closures (0)"}) {
    EXPECT_TRUE(evoslam::FindText(image, label, evoslam::kInkColor, 2)) << label;
  }
  // The walls above the legend span most of the picture.
  const int legend = evoslam::FindText(image, "estimate", evoslam::kInkColor, 2)->y();
  int left = image.width(), right = -1, top = image.height(), bottom = -1;
  for (int y = 0; y < legend; ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (!(image.at(x, y) == evoslam::Rgb{0, 0, 0})) continue;
      left = std::min(left, x);
      right = std::max(right, x);
      top = std::min(top, y);
      bottom = std::max(bottom, y);
    }
  }
  EXPECT_GT(right - left, 0.85 * image.width());
  EXPECT_GT(bottom - top, 0.7 * image.height());
  EXPECT_GT(evoslam::CountPixels(image, evoslam::kTruthColor),
            evoslam::CountPixels(image, evoslam::kEstimateColor));
}

TEST_F(CliTest, SlamMapsASimulatedWorld) {
  const std::string slam =
      "slam --world office-cluster --max-scans 120 --generations 5 --global-every 50 --seed 2";
  const Result r = RunCli(slam + " --out " + Path("run"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f :
       {"log.clf", "truth.txt", "world.lines", "trajectory.txt", "trajectory.tum", "map.pgm",
        "map.yaml", "map.png", "map_trajectory.png", "report.json", "summary.txt"}) {
    EXPECT_TRUE(fs::exists(dir_ / "run" / f)) << f;
  }
  EXPECT_NE(r.output.find("RMS error vs ground truth"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(Path("run/map_trajectory.png")), std::string::npos) << r.output;
  EXPECT_EQ(evoslam::ReadTrajectory(dir_ / "run" / "trajectory.txt").size(), 120u);
  const evoslam::proto::SlamReport report = ReadSlamReport(dir_ / "run" / "report.json");
  EXPECT_EQ(report.scans(), 120u);
  EXPECT_EQ(report.params().rss().global().generations(), 5u);
  EXPECT_EQ(report.absolute_errors().poses(), 120u);
  EXPECT_LT(report.absolute_errors().rms_translation_m(),
            0.5 * report.odometry_absolute_errors().rms_translation_m());
  EXPECT_GE(report.rss().global_searches_size(), 2);  // every 50 scans

  const Result local = RunCli(slam + " --local-only --out " + Path("local"));
  ASSERT_EQ(local.status, 0) << local.output;
  const evoslam::proto::SlamReport local_report = ReadSlamReport(dir_ / "local" / "report.json");
  EXPECT_FALSE(local_report.params().rss().global().enabled());
  EXPECT_EQ(local_report.rss().global_searches_size(), 0);
  EXPECT_EQ(local_report.rss().global_evaluations(), 0u);
  EXPECT_EQ(evoslam::ReadTrajectory(dir_ / "local" / "trajectory.txt").size(), 120u);
}

// bench/seed_sweep.sh, which made accuracy.md's per-seed tables: each row is the error its run
// reported, the last line their statistics, and running seeds side by side changes neither.
TEST_F(CliTest, SeedSweepReportsEachSeedsErrorAndTheirSpread) {
  const std::string slam = " -- --max-scans 100 --local-only";
  const Result one = RunSweep("1-3 " + Path("one") + slam);
  ASSERT_EQ(one.status, 0) << one.output;
  const Result two = RunSweep("-j 2 1,2-3 " + Path("two") + slam);
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_EQ(ReadAll(dir_ / "two" / "sweep.tsv"), ReadAll(dir_ / "one" / "sweep.tsv"));

  std::istringstream tsv(ReadAll(dir_ / "one" / "sweep.tsv"));
  std::string header;
  std::getline(tsv, header);
  EXPECT_EQ(header, "seed\terror\tunit\tloops\tsearches_applied");
  std::vector<double> errors;
  for (int seed = 1; seed <= 3; ++seed) {
    int read_seed = 0;
    double error = 0;
    std::string unit;
    ASSERT_TRUE(tsv >> read_seed >> error >> unit) << "no row for seed " << seed;
    std::getline(tsv, header);
    EXPECT_EQ(read_seed, seed);
    EXPECT_EQ(unit, "cm");
    const auto report =
        ReadSlamReport(dir_ / "one" / ("seed-" + std::to_string(seed)) / "report.json");
    EXPECT_NEAR(error, 100 * report.absolute_errors().aligned_rms_translation_m(), 1e-9);
    errors.push_back(error);
  }
  ASSERT_NE(errors[0], errors[1]) << "the seeds should differ for the statistics to mean much";
  const double mean = (errors[0] + errors[1] + errors[2]) / 3;
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  const auto best = std::min_element(errors.begin(), errors.end()) - errors.begin();
  const auto worst = std::max_element(errors.begin(), errors.end()) - errors.begin();
  char expected[200];
  std::snprintf(expected, sizeof expected,
                "3 seeds: mean %.3f cm, median %.3f, best %.2f (seed %d), worst %.2f (seed %d)\n",
                mean, sorted[1], errors[best], static_cast<int>(best) + 1, errors[worst],
                static_cast<int>(worst) + 1);
  EXPECT_NE(one.output.find(expected), std::string::npos) << expected << one.output;
}

// A seed whose run fails is named with the run's error, and the sweep fails; usage errors are
// refused before anything runs.
TEST_F(CliTest, SeedSweepNamesTheSeedsThatFailed) {
  const Result failed = RunSweep("4 " + Path("bad") + " -- --log " + Path("missing.clf"));
  EXPECT_EQ(failed.status, 1) << failed.output;
  EXPECT_NE(failed.output.find("seed 4 failed: evoslam: error: " + Path("missing.clf")),
            std::string::npos)
      << failed.output;

  const Result usage = RunSweep("1-3 " + Path("usage"));
  EXPECT_EQ(usage.status, 2) << usage.output;
  EXPECT_NE(usage.output.find("expected SEEDS OUT -- SLAM_ARGS"), std::string::npos)
      << usage.output;
  EXPECT_FALSE(fs::exists(dir_ / "usage"));
  EXPECT_EQ(RunSweep("3-1 " + Path("usage") + " --").status, 2);
}

// bench/compare_sweeps.sh pairs two sweeps' errors by seed, over the seeds both hold.
TEST_F(CliTest, CompareSweepsPairsTheSeedsBothSweepsHold) {
  const std::string header = "seed\terror\tunit\tloops\tsearches_applied\n";
  fs::create_directory(dir_ / "before");
  std::ofstream(dir_ / "before" / "sweep.tsv")
      << header << "1\t0.020\tm\t3\t3\n2\t0.018\tm\t2\t2\n3\t0.025\tm\t5\t4\n"
      << "4\t0.017\tm\t1\t1\n";
  std::ofstream(Path("after.tsv")) << header << "2\t0.018\tm\t2\t2\n3\t0.019\tm\t4\t4\n"
                                   << "4\t0.0175\tm\t1\t1\n5\t0.030\tm\t9\t9\n";
  const Result r = RunCompare(Path("before"), Path("after.tsv"));
  ASSERT_EQ(r.status, 0) << r.output;
  // Seeds 2, 3 and 4: one the same, one better, one worse.
  const std::array<double, 3> before{0.018, 0.025, 0.017}, after{0.018, 0.019, 0.0175};
  std::array<double, 3> d;
  for (std::size_t i = 0; i < 3; ++i) d[i] = after[i] - before[i];
  const double mean = (d[0] + d[1] + d[2]) / 3;
  double squares = 0;
  for (const double x : d) squares += (x - mean) * (x - mean);
  const double t = mean / std::sqrt(squares / 2 / 3);
  char expected[240];
  std::snprintf(expected, sizeof expected,
                "3 seeds in both: mean %.5f -> %.5f m, median %.5f -> %.5f\n"
                "paired difference %.5f m (t = %.2f over 3 seeds); better 1, worse 1, the same 1\n",
                (before[0] + before[1] + before[2]) / 3, (after[0] + after[1] + after[2]) / 3,
                before[0], after[0], mean, t);
  EXPECT_NE(r.output.find(expected), std::string::npos) << expected << r.output;
  EXPECT_NE(r.output.find("seed 3      0.0250 -> 0.0190 m\n"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("seed 1 "), std::string::npos) << "seed 1 is in one sweep only";

  std::ofstream(Path("cm.tsv")) << header << "3\t2.5\tcm\t0\t0\n";
  const Result units = RunCompare(Path("before"), Path("cm.tsv"));
  EXPECT_EQ(units.status, 2) << units.output;
  EXPECT_NE(units.output.find("seed 3 is in m in"), std::string::npos) << units.output;
  std::ofstream(Path("other.tsv")) << header << "9\t0.02\tm\t0\t0\n";
  EXPECT_EQ(RunCompare(Path("before"), Path("other.tsv")).status, 1);
  const Result missing = RunCompare(Path("before"), Path("nowhere"));
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find(Path("nowhere") + "' is neither"), std::string::npos)
      << missing.output;
}

// A disk that fills while the results are written fails the run, naming the file: a run that
// printed its summary and returned 0 would leave the user with a file that is not there.
TEST_F(CliTest, AnOutputThatCannotBeWrittenFailsTheRunNamingIt) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full to stand for a full disk";
  fs::create_directory(dir_ / "full");
  fs::create_symlink("/dev/full", dir_ / "full" / "summary.txt");
  const Result r = RunCli("slam --max-scans 20 --local-only --out " + Path("full"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("cannot write " + Path("full/summary.txt") + ": No space left"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("wrote "), std::string::npos) << r.output;
}

// A bad log found by the service is named as the user named it, with its line.
TEST_F(CliTest, SlamOnAMalformedLogFailsNamingFileAndLine) {
  std::ofstream(Path("broken.clf"))
      << "# header\nODOM 0 0 0 0 0 0 1.0 nohost 0\nFLASER 3 1.0 2.0 x 0 0 0 0 0 0 1.0 nohost 0\n";
  const Result r = RunCli("slam --log " + Path("broken.clf") + " --out " + Path("o"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(Path("broken.clf") + ":3:"), std::string::npos) << r.output;
}

// `plot` draws a run's pictures again from its folder, the same bytes the run wrote; elsewhere
// with --out; and beside another run's estimate with --compare.
TEST_F(CliTest, PlotRedrawsARunsPicturesFromItsFolder) {
  const std::string slam = "slam --world office-boxes --max-scans 60 --local-only";
  ASSERT_EQ(RunCli(slam + " --out " + Path("a")).status, 0);
  const std::string map = ReadAll(dir_ / "a" / "map.png");
  const std::string picture = ReadAll(dir_ / "a" / "map_trajectory.png");
  fs::remove(dir_ / "a" / "map.png");
  fs::remove(dir_ / "a" / "map_trajectory.png");
  const Result plot = RunCli("plot " + Path("a"));
  ASSERT_EQ(plot.status, 0) << plot.output;
  EXPECT_NE(plot.output.find("wrote " + Path("a/map_trajectory.png")), std::string::npos)
      << plot.output;
  EXPECT_TRUE(ReadAll(dir_ / "a" / "map.png") == map);
  EXPECT_TRUE(ReadAll(dir_ / "a" / "map_trajectory.png") == picture);

  const Result out = RunCli("plot " + Path("a") + " --out " + Path("pictures/a.png"));
  ASSERT_EQ(out.status, 0) << out.output;
  EXPECT_TRUE(ReadAll(dir_ / "pictures" / "a.png") == picture);

  ASSERT_EQ(RunCli(slam + " --seed 2 --out " + Path("b")).status, 0);
  const Result compare = RunCli("plot " + Path("a") + " --compare " + Path("b"));
  ASSERT_EQ(compare.status, 0) << compare.output;
  const evoslam::Image both = evoslam::ReadPng(dir_ / "a" / "compare.png");
  EXPECT_GT(evoslam::CountPixels(both, evoslam::kComparedColor), 500);
  EXPECT_TRUE(evoslam::FindText(both, Path("b"), evoslam::kInkColor, 2));
  EXPECT_TRUE(ReadAll(dir_ / "a" / "map_trajectory.png") == picture) << "left as it was";

  // A localization's folder too.
  ASSERT_EQ(RunCli("simulate --world s-corridor --max-scans 10 --out " + Path("sim")).status, 0);
  ASSERT_EQ(RunCli("localize --map " + Path("sim/world.lines") + " --log " + Path("sim/log.clf") +
                   " --out " + Path("loc"))
                .status,
            0);
  const std::string located = ReadAll(dir_ / "loc" / "map.png");
  fs::remove(dir_ / "loc" / "map.png");
  ASSERT_EQ(RunCli("plot " + Path("loc")).status, 0);
  EXPECT_TRUE(ReadAll(dir_ / "loc" / "map.png") == located);
}

// A folder that is not there, or lacks a file the pictures need, is named with what it lacks
// (exit 1); a wrong flag is refused before any folder is read (exit 2).
TEST_F(CliTest, PlotSaysWhatItLacksAndWhere) {
  const Result missing = RunCli("plot " + Path("nowhere"));
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find(Path("nowhere") + " is not a folder"), std::string::npos)
      << missing.output;

  ASSERT_EQ(RunCli("slam --max-scans 20 --local-only --out " + Path("run")).status, 0);
  fs::remove(dir_ / "run" / "odometry.txt");
  const Result lacking = RunCli("plot " + Path("run"));
  EXPECT_EQ(lacking.status, 1) << lacking.output;
  EXPECT_NE(lacking.output.find(Path("run") + " has no odometry.txt"), std::string::npos)
      << lacking.output;

  for (const std::string& args : std::vector<std::string>{"", "--no-such-flag " + Path("run"),
                                                          Path("nowhere") + " --compare"}) {
    const Result r = RunCli("plot " + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_EQ(r.output.find("is not a folder"), std::string::npos) << r.output;
  }
}

TEST_F(CliTest, InfoDescribesTheIntelLog) {
  const fs::path log = fs::path(EVOSLAM_DATA_DIR) / "intel.clf.bz2";
  if (!fs::exists(log)) GTEST_SKIP() << "real data absent: " << log;
  const Result r = RunCli("info " + log.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("13631"), std::string::npos) << r.output;
}

}  // namespace
