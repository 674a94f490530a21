// One name for each thing across the subcommands: the names in use work, the deprecated ones
// still do (with a warning on stderr) and give the same result; the log is given as the
// positional or as --log; --help shows the names in use, every default and what is required.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common/util/temp_dir.h"
#include "tests/cli_testing.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::RunCli;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every --name that `help` mentions, in an option's line or in its description.
std::set<std::string> NamesIn(const std::string& help) {
  static const std::regex name(R"(--[A-Za-z0-9][A-Za-z0-9-]*)");
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(help.begin(), help.end(), name); it != std::sregex_iterator();
       ++it) {
    names.insert(it->str());
  }
  return names;
}

// The line of --help that lists `option` ("--out", or a positional's name), "" if none does.
std::string LineOf(const std::string& help, const std::string& option) {
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    const std::size_t start = line.find_first_not_of(' ');
    if (start == 2 || start == 4) {
      if (line.compare(start, option.size() + 1, option + " ") == 0) return line;
    }
  }
  return "";
}

// tune's table without its times, which vary: island count, population per island, evaluations
// and mean fitness of each row.
std::vector<std::string> TuneRows(const std::string& output) {
  std::vector<std::string> rows;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string islands, population, evaluations, seconds, fitness;
    if (!(fields >> islands >> population >> evaluations >> seconds >> fitness)) continue;
    if (islands.find_first_not_of("0123456789") != std::string::npos) continue;
    rows.push_back(islands + " " + population + " " + evaluations + " " + fitness);
  }
  return rows;
}

class CliVocabularyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto sim =
        RunCli("simulate --world s-corridor --max-scans 4 --seed 2 --out " + Path("sim"));
    ASSERT_EQ(sim.status, 0) << sim.output;
    log_ = Path("sim/log.clf");
    map_ = Path("sim/world.lines");
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  TempDir dir_;
  std::string log_, map_;
};

TEST_F(CliVocabularyTest, LocalizeTakesPopulationGenerationsAndResolution) {
  const std::string job = "localize --map " + map_ + " --log " + log_ + " --max-scans 3";
  const auto now = RunCli(job + " --population 6 --generations 3 --out " + Path("now"), true);
  ASSERT_EQ(now.status, 0) << now.error;
  EXPECT_THAT(now.error, Not(HasSubstr("deprecated")));
  const auto old = RunCli(job + " --pop 6 --gen 3 --out " + Path("old"), true);
  ASSERT_EQ(old.status, 0) << old.error;
  EXPECT_THAT(old.error, HasSubstr("--pop is deprecated; use --population"));
  EXPECT_THAT(old.error, HasSubstr("--gen is deprecated; use --generations"));
  EXPECT_THAT(old.output, Not(HasSubstr("deprecated")));
  EXPECT_THAT(old.output, HasSubstr("population 6, generations 3"));
  EXPECT_EQ(ReadAll(dir_ / "now" / "trajectory.txt"), ReadAll(dir_ / "old" / "trajectory.txt"));

  // A deprecated name's bad value is refused under the name given.
  const auto bad = RunCli(job + " --pop 1 --out " + Path("bad"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_THAT(bad.output, HasSubstr("--pop (deprecated; use --population)"));

  const std::string grid =
      "localize --map-from-log " + log_ + " --log " + log_ + " --max-scans 2 --generations 2";
  const auto cells = RunCli(grid + " --resolution 0.1 --out " + Path("cells"), true);
  ASSERT_EQ(cells.status, 0) << cells.error;
  const auto old_cells = RunCli(grid + " --grid-resolution 0.1 --out " + Path("old-cells"), true);
  ASSERT_EQ(old_cells.status, 0) << old_cells.error;
  EXPECT_THAT(old_cells.error, HasSubstr("--grid-resolution is deprecated; use --resolution"));
  EXPECT_THAT(ReadAll(dir_ / "cells" / "map.yaml"), HasSubstr("resolution: 0.1\n"));
  EXPECT_EQ(ReadAll(dir_ / "cells" / "map.yaml"), ReadAll(dir_ / "old-cells" / "map.yaml"));
  EXPECT_EQ(ReadAll(dir_ / "cells" / "map.pgm"), ReadAll(dir_ / "old-cells" / "map.pgm"));
}

TEST_F(CliVocabularyTest, SlamTakesLocalPopulationForTheDeprecatedParticles) {
  const auto now = RunCli("slam --print-params --local-population 7", true);
  ASSERT_EQ(now.status, 0) << now.error;
  EXPECT_THAT(now.output, HasSubstr("particles: 7\n"));
  const auto old = RunCli("slam --print-params --particles 7", true);
  ASSERT_EQ(old.status, 0) << old.error;
  EXPECT_EQ(old.output, now.output);
  EXPECT_THAT(old.error, HasSubstr("--particles is deprecated; use --local-population"));
  // The warning is a log line like any other: --log-level, after the subcommand too, silences it.
  const auto quiet = RunCli("slam --print-params --particles 7 --log-level error", true);
  ASSERT_EQ(quiet.status, 0) << quiet.error;
  EXPECT_EQ(quiet.error, "");
}

TEST_F(CliVocabularyTest, TuneTakesIslandCountsAndTotalPopulation) {
  const std::string job = "tune --map " + map_ + " --log " + log_ +
                          " --max-scans 2 --generations 2 --seeds 1 --threads 1";
  const auto now = RunCli(job + " --island-counts 1,2 --total-population 8", true);
  ASSERT_EQ(now.status, 0) << now.error;
  const auto old = RunCli(job + " --islands 1,2 --total-pop 8", true);
  ASSERT_EQ(old.status, 0) << old.error;
  EXPECT_THAT(old.error, HasSubstr("--islands is deprecated; use --island-counts"));
  EXPECT_THAT(old.error, HasSubstr("--total-pop is deprecated; use --total-population"));
  const std::vector<std::string> rows = TuneRows(now.output);
  // Each count's row: the islands, the population of each, the same evaluations.
  EXPECT_THAT(rows, ::testing::ElementsAre(::testing::StartsWith("1 8 48 "),
                                           ::testing::StartsWith("2 4 48 ")))
      << now.output;
  EXPECT_EQ(TuneRows(old.output), rows) << old.output;

  const auto population = RunCli(job + " --population 4");
  EXPECT_EQ(population.status, 2) << population.output;
  EXPECT_THAT(population.output, HasSubstr("use --total-population"));
}

TEST_F(CliVocabularyTest, EveryCommandTakesItsLogAsThePositionalOrAsLog) {
  // info and eval print the same; slam and localize write the same trajectory.
  for (const std::string& command : {std::string("info"), "eval --truth " + log_}) {
    const auto positional = RunCli(command + " " + log_);
    ASSERT_EQ(positional.status, 0) << command << ": " << positional.output;
    const auto named = RunCli(command + " --log " + log_);
    ASSERT_EQ(named.status, 0) << command << ": " << named.output;
    EXPECT_EQ(named.output, positional.output) << command;
    // Both, naming the same log, are one log.
    const auto both = RunCli(command + " " + log_ + " --log " + log_);
    EXPECT_EQ(both.status, 0) << command << ": " << both.output;
    EXPECT_EQ(both.output, positional.output) << command;
  }
  for (const std::string& command : {std::string("slam --local-only --max-scans 3"),
                                     "localize --map " + map_ + " --max-scans 3 --generations 2"}) {
    const auto positional = RunCli(command + " " + log_ + " --out " + Path("positional"));
    ASSERT_EQ(positional.status, 0) << command << ": " << positional.output;
    const auto named = RunCli(command + " --log " + log_ + " --out " + Path("named"));
    ASSERT_EQ(named.status, 0) << command << ": " << named.output;
    EXPECT_EQ(ReadAll(dir_ / "named" / "trajectory.txt"),
              ReadAll(dir_ / "positional" / "trajectory.txt"))
        << command;
    fs::remove_all(dir_ / "named");
    fs::remove_all(dir_ / "positional");
  }
}

TEST_F(CliVocabularyTest, TwoDifferentLogsAreRefusedNamingBothSpellings) {
  // Neither file exists: the refusal comes before anything is read or written.
  const std::string a = Path("a.clf"), b = Path("b.clf");
  for (const auto& [command, positional] : std::vector<std::pair<std::string, std::string>>{
           {"info", "log"},
           {"eval --truth " + log_, "trajectory"},
           {"slam --out " + Path("o"), "log"},
           {"localize --map " + map_ + " --out " + Path("o"), "log"}}) {
    const auto r = RunCli(command + " " + a + " --log " + b);
    EXPECT_EQ(r.status, 2) << command << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(positional + " or --log: two different files")) << command;
    EXPECT_THAT(r.output, HasSubstr("'" + a + "'")) << command;
    EXPECT_THAT(r.output, HasSubstr("'" + b + "'")) << command;
  }
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(CliVocabularyTest, HelpNamesEachThingByItsNameInUse) {
  const std::set<std::string> deprecated = {"--pop", "--gen", "--grid-resolution", "--total-pop",
                                            "--particles"};
  for (const auto& [command, names] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"info", {"--log"}},
           {"eval", {"--log"}},
           {"simulate", {"--out", "--max-scans", "--seed"}},
           {"slam",
            {"--log", "--local-population", "--local-iterations", "--generations", "--islands",
             "--resolution"}},
           {"localize",
            {"--log", "--map", "--population", "--generations", "--islands", "--resolution"}},
           {"tune",
            {"--log", "--map", "--island-counts", "--total-population", "--generations",
             "--resolution"}}}) {
    const auto r = RunCli(command + " --help");
    ASSERT_EQ(r.status, 0) << command << ": " << r.output;
    const std::set<std::string> shown = NamesIn(r.output);
    for (const std::string& name : names) EXPECT_TRUE(shown.contains(name)) << command << name;
    for (const std::string& name : deprecated)
      EXPECT_FALSE(shown.contains(name)) << command << name;
  }
  // tune's --islands, a list, is --island-counts; a number of islands is localize's --islands.
  EXPECT_FALSE(NamesIn(RunCli("tune --help").output).contains("--islands"));
}

TEST_F(CliVocabularyTest, HelpShowsEveryDefaultAndMarksWhatIsRequired) {
  for (const auto& [command, option, shown] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"slam", "--method", "=rss"},
           {"slam", "--local-population", "=10"},
           {"slam", "--resolution", "=0.06"},
           {"slam", "--preset", "=mu+lambda-002"},
           {"slam", "--out", "required unless --detach"},
           {"localize", "--resolution", "=0.05"},
           {"localize", "--population", "=25"},
           {"localize", "--log", "REQUIRED"},
           {"localize", "log", "REQUIRED"},
           {"localize", "--out", "required unless --detach"},
           {"tune", "--island-counts", "=1,2,4,8"},
           {"tune", "--total-population", "=40"},
           {"tune", "--seeds", "=3"},
           {"simulate", "--beams", "=361"},
           {"simulate", "--out", "REQUIRED"},
           {"info", "log", "REQUIRED"},
           {"info", "--log", "REQUIRED"},
           {"eval", "trajectory", "REQUIRED"},
           {"eval", "--log", "REQUIRED"},
           {"plot", "run", "REQUIRED"},
           {"keygen", "--name", "REQUIRED"},
           {"keygen", "--out", "=."},
           {"result", "job", "REQUIRED"},
           {"result", "--out", "REQUIRED"},
           {"jobs", "--timeout", "=30"}}) {
    const auto r = RunCli(command + " --help");
    ASSERT_EQ(r.status, 0) << command << ": " << r.output;
    const std::string line = LineOf(r.output, option);
    EXPECT_THAT(line, HasSubstr(shown)) << command << " " << option << ":\n" << r.output;
  }
  // Exactly one of two: the map of localize and tune, what eval measures against.
  for (const auto& [command, first] : std::vector<std::pair<std::string, std::string>>{
           {"localize", "--map"}, {"tune", "--map"}, {"eval", "--relations"}}) {
    const std::string help = RunCli(command + " --help").output;
    const std::size_t rule = help.find("[Exactly 1 of the following options is required]");
    ASSERT_NE(rule, std::string::npos) << command << ":\n" << help;
    EXPECT_NE(help.find("  " + first + " ", rule), std::string::npos) << command;
  }
  const auto no_map = RunCli("localize --log " + log_ + " --out " + Path("o"));
  EXPECT_EQ(no_map.status, 2) << no_map.output;
  EXPECT_THAT(no_map.output, HasSubstr("--map"));
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

}  // namespace
}  // namespace evoslam
