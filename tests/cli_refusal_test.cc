// The command line refuses what cannot work before it reads or writes anything, and never
// crashes or hangs on it: exit status 2 for a command line, 1 for an input that cannot be used.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "common/util/temp_dir.h"
#include "tests/cli_testing.h"

namespace evoslam {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::RunCli;

class CliRefusalTest : public ::testing::Test {
 protected:
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& content) const {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return Path(name);
  }
  // What the folder holds, so that a test can tell that a refused run wrote nothing.
  std::size_t Entries() const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir_.path()), fs::directory_iterator()));
  }

  TempDir dir_;
};

TEST_F(CliRefusalTest, AMistypedSubcommandIsAnsweredWithTheNearestOne) {
  const auto r = RunCli("slm --out " + Path("o"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("'slm' is not a subcommand; did you mean 'slam'?"));
  const auto far = RunCli("compile");
  EXPECT_EQ(far.status, 2) << far.output;
  EXPECT_THAT(far.output, HasSubstr("`evoslam --help` lists them"));
}

TEST_F(CliRefusalTest, AMistypedChoiceListsTheChoicesAndTheNearestOne) {
  const auto world = RunCli("slam --world office-clustr --out " + Path("o"));
  EXPECT_EQ(world.status, 2) << world.output;
  EXPECT_THAT(world.output, HasSubstr("'office-clustr' is not one of office-boxes,"));
  EXPECT_THAT(world.output, HasSubstr("did you mean 'office-cluster'?"));
  const auto optimizer = RunCli("localize --optimizer jd --log x.clf --map x.lines");
  EXPECT_EQ(optimizer.status, 2) << optimizer.output;
  EXPECT_THAT(optimizer.output, HasSubstr("--optimizer: 'jd' is not one of"));
  EXPECT_EQ(Entries(), 0u);
}

TEST_F(CliRefusalTest, TheLogLevelMayFollowTheSubcommand) {
  const auto r = RunCli("simulate --max-scans 3 --log-level warn --out " + Path("sim"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "sim" / "log.clf"));
}

TEST_F(CliRefusalTest, HelpShowsEveryDefault) {
  const auto r = RunCli("localize --help");
  ASSERT_EQ(r.status, 0) << r.output;
  // Options with a value and a default, as --help lists them: "--population UINT:... =25".
  for (const auto& [option, value] :
       std::vector<std::pair<std::string, std::string>>{{"--population", "25"},
                                                        {"--generations", "25"},
                                                        {"--window", "0.6"},
                                                        {"--fitness", "f3"}}) {
    const std::size_t at = r.output.find("  " + option + " ");
    ASSERT_NE(at, std::string::npos) << option;
    const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
    EXPECT_THAT(line, HasSubstr("=" + value)) << line;
  }
  EXPECT_THAT(r.output, HasSubstr("REQUIRED"));
}

TEST_F(CliRefusalTest, AnOutputFolderThatCannotBeWrittenIsRefusedBeforeTheLogIsRead) {
  const std::string file = Write("taken", "a file, not a folder\n");
  // The log does not exist: a refusal that names --out came before any reading.
  for (const std::string& out : {file, file + "/below"}) {
    const auto slam = RunCli("slam --log " + Path("missing.clf") + " --out " + out);
    EXPECT_EQ(slam.status, 2) << slam.output;
    EXPECT_THAT(slam.output, HasSubstr("--out"));
    EXPECT_THAT(slam.output, HasSubstr("is not a folder"));
    const auto localize = RunCli("localize --map " + Path("missing.lines") + " --log " +
                                 Path("missing.clf") + " --out " + out);
    EXPECT_EQ(localize.status, 2) << localize.output;
    EXPECT_THAT(localize.output, HasSubstr("--out"));
    const auto simulate = RunCli("simulate --out " + out);
    EXPECT_EQ(simulate.status, 2) << simulate.output;
    EXPECT_THAT(simulate.output, HasSubstr("--out"));
  }
  EXPECT_EQ(Entries(), 1u);
}

TEST_F(CliRefusalTest, ASimulatedDriveWhoseMapCannotBeBuiltLeavesNothingBehind) {
  const auto r =
      RunCli("slam --world office-cluster --max-scans 20 --resolution 1e-9 --out " + Path("slam"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "slam")) << r.output;
  EXPECT_EQ(Entries(), 0u);
}

// 3 mm cells on two scans' reach: a search map of 144 M cells, about 1.2 GB. Under a 1.5 GB
// address space (of which the process maps half before the run) it cannot fit, and is refused
// before it starts, saying how much it needs and for what.
TEST_F(CliRefusalTest, ARunThatCannotFitInMemoryIsRefusedBeforeItStarts) {
#ifdef EVOSLAM_SANITIZED
  GTEST_SKIP() << "AddressSanitizer maps terabytes of shadow memory: no address-space limit holds";
#endif
  const auto r = testing::RunCommand("ulimit -v 1500000 && " + std::string(EVOSLAM_CLI) +
                                     " slam --world office-cluster --max-scans 2 --resolution "
                                     "0.003 --out " +
                                     Path("slam"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("needs about 1.2 GB of memory"));
  EXPECT_THAT(r.output, HasSubstr("12045 x 12001 cells of 0.003 m (--resolution)"));
  EXPECT_THAT(r.output, HasSubstr("available"));
  EXPECT_EQ(Entries(), 0u);
}

TEST_F(CliRefusalTest, StepsTooFineForAnyMachineAreRefusedNamingTheFlag) {
  const std::string sim = Path("sim");
  ASSERT_EQ(RunCli("simulate --world s-corridor --max-scans 5 --out " + sim).status, 0);
  const std::string job =
      "localize --map " + sim + "/world.lines --log " + sim + "/log.clf --out " + Path("loc");
  const auto heading = RunCli(job + " --heading-step 1e-9");
  EXPECT_EQ(heading.status, 2) << heading.output;
  EXPECT_THAT(heading.output, HasSubstr("--heading-step"));
  const auto lattice = RunCli(job + " --optimizer exhaustive --exhaustive-step 1e-9");
  EXPECT_EQ(lattice.status, 2) << lattice.output;
  EXPECT_THAT(lattice.output, HasSubstr("--exhaustive-step"));
  const auto step = RunCli("simulate --step 1e-9 --max-scans 5 --out " + Path("fine"));
  EXPECT_EQ(step.status, 2) << step.output;
  EXPECT_THAT(step.output, HasSubstr("--step"));
  EXPECT_FALSE(fs::exists(dir_ / "loc"));
  EXPECT_FALSE(fs::exists(dir_ / "fine"));
}

TEST_F(CliRefusalTest, ALogWithoutScansIsAnErrorNotAnEmptyDescription) {
  const std::string empty = Write("empty.clf", "");
  const std::string noise = Write("noise.clf", "\x17\x9c\xff garbage\n\x01\x02\n");
  const std::string odometry = Write("odometry.clf", "ODOM 0 0 0 0 0 0 1.0 host 1.0\n");
  for (const std::string& log : {empty, noise, odometry}) {
    const auto r = RunCli("info " + log);
    EXPECT_EQ(r.status, 1) << log << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(log + ": no laser scans"));
  }
  EXPECT_THAT(RunCli("info " + odometry).output, HasSubstr("only 1 odometry reading"));
}

TEST_F(CliRefusalTest, LocalizingInAMapWithoutWallsIsAnError) {
  const std::string sim = Path("sim");
  ASSERT_EQ(RunCli("simulate --world s-corridor --max-scans 5 --out " + sim).status, 0);
  const std::string empty = Write("empty.lines", "");
  const auto r =
      RunCli("localize --map " + empty + " --log " + sim + "/log.clf --out " + Path("loc"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr(empty + ": the map has no walls"));
  EXPECT_FALSE(fs::exists(dir_ / "loc"));
}

TEST_F(CliRefusalTest, MoreEmbeddedWorkersThanTheProcessCanOpenAreRefused) {
  // 256 files leave room for far fewer than 200 workers, each a socket and an eventfd.
  const auto r = testing::RunCommand("ulimit -n 256 && " + std::string(EVOSLAM_CLI) +
                                     " slam --max-scans 20 --workers 200 --out " + Path("o"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--workers: 200 is more than this process can embed"));
  EXPECT_EQ(Entries(), 0u);
}

TEST_F(CliRefusalTest, TheServiceProgramsLogToStderr) {
  const std::string db = Path("taken") + "/jobs.db";
  Write("taken", "a file where the database's folder should be\n");
  const auto r = testing::RunCommand(std::string(EVOSLAM_COORDINATOR) + " --db " + db, true);
  EXPECT_EQ(r.status, 1) << r.error;
  EXPECT_EQ(r.output, "");
  EXPECT_THAT(r.error, HasSubstr("[error]"));
}

// A simulated corridor log rewritten by awk: `program` sees each FLASER line with `scan` its index
// and `n` its beam count ($(6+n) is the odometry's x, $(7+n) its y, $(9+n) the timestamp).
std::string RewrittenLog(const std::string& dir, const std::string& program) {
  const std::string sim = dir + "/sim";
  EXPECT_EQ(RunCli("simulate --world s-corridor --max-scans 60 --seed 2 --out " + sim).status, 0);
  const std::string log = dir + "/edited.clf";
  const auto r = testing::RunCommand("awk '/^FLASER/ { n = $2; " + program +
                                     "; scan++ } { print }' " + sim + "/log.clf > " + log);
  EXPECT_EQ(r.status, 0) << r.output;
  return log;
}

TEST_F(CliRefusalTest, AnOdometryJumpIsReportedAtTheScansWhereItHappened) {
  // From scan 30 on the odometry reads 10 m further along: below the refusal (twice the laser's
  // 8 m reach), far beyond the log's pace.
  const std::string log = RewrittenLog(dir_.path().string(), "if (scan >= 30) { $(6+n) += 10 }");
  const auto info = RunCli("info " + log);
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_THAT(info.output, HasSubstr("m from scan 29 to 30"));
  const auto slam = RunCli("slam --log " + log + " --out " + Path("slam"));
  EXPECT_EQ(slam.status, 0) << slam.output;
  EXPECT_THAT(slam.output, HasSubstr("odometry jumps"));
  EXPECT_THAT(slam.output, HasSubstr("m from scan 29 to 30"));
  const auto localize = RunCli("localize --map " + Path("sim/world.lines") + " --log " + log +
                               " --use-odometry --out " + Path("loc"));
  EXPECT_EQ(localize.status, 0) << localize.output;
  EXPECT_THAT(localize.output, HasSubstr("m from scan 29 to 30"));
}

TEST_F(CliRefusalTest, AJumpTooLongToMapIsRefusedAtTheScansWhereItHappened) {
  // The robot stands still from scan 1 to 12 (the odometry repeats: a stall the run would fill
  // in), and scan 9's odometry reads a kilometre away.
  const std::string log = RewrittenLog(
      dir_.path().string(),
      "if (scan == 0) { x0 = $(6+n); y0 = $(7+n) } if (scan >= 1 && scan <= 12) { $(6+n) = x0 + "
      "(scan >= 9 ? 1000 : 0); $(7+n) = y0 }");
  const auto slam = RunCli("slam --log " + log + " --out " + Path("slam"));
  EXPECT_EQ(slam.status, 1) << slam.output;
  EXPECT_THAT(slam.output, HasSubstr("m from scan 8 to scan 9"));
  // Said once, as the command's own failure: no job, no coordinator.
  EXPECT_EQ(slam.output.find("odometry moves"), slam.output.rfind("odometry moves")) << slam.output;
  EXPECT_THAT(slam.output, ::testing::Not(HasSubstr("job-")));
}

TEST_F(CliRefusalTest, TimestampsThatGoBackAreReportedAndTheLogLastsFromEarliestToLatest) {
  const std::string log = RewrittenLog(dir_.path().string(), "if (scan >= 20) { $(9+n) -= 58.43 }");
  const auto slam = RunCli("slam --log " + log + " --out " + Path("slam"));
  EXPECT_EQ(slam.status, 0) << slam.output;
  EXPECT_THAT(slam.output, HasSubstr("timestamps go back 1 time"));
  EXPECT_THAT(slam.output, HasSubstr("at scan 20 by"));
  EXPECT_THAT(slam.output, ::testing::Not(HasSubstr(" -")));
  EXPECT_THAT(RunCli("info " + log).output, HasSubstr("at scan 20 by"));
}

TEST_F(CliRefusalTest, LinesSkippedUnderLenientAreCountedInTheReports) {
  const std::string log =
      RewrittenLog(dir_.path().string(), "if (scan == 5) { $0 = \"FLASER 3 x\" }");
  const auto slam = RunCli("slam --lenient --log " + log + " --out " + Path("slam"));
  EXPECT_EQ(slam.status, 0) << slam.output;
  EXPECT_THAT(slam.output, HasSubstr("skipped 1 malformed line of the log"));
  // Named as the user named it, never as the service's copy.
  EXPECT_THAT(slam.output, HasSubstr(log + ": skipped 1 malformed line (the first, line"));
  EXPECT_THAT(slam.output, ::testing::Not(HasSubstr("evoslam-coordinator")));
  std::ifstream report(dir_ / "slam" / "report.json");
  const std::string json((std::istreambuf_iterator<char>(report)),
                         std::istreambuf_iterator<char>());
  EXPECT_THAT(json, HasSubstr("\"skipped_lines\": \"1\""));
}

}  // namespace
}  // namespace evoslam
