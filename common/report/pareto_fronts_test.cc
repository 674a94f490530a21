#include "common/report/pareto_fronts.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "common/report/pareto_testing.h"
#include "common/util/error_testing.h"

namespace evoslam {
namespace {

using testing::ErrorOf;
using testing::MakeFront;
using testing::TwoWindowFronts;

// Expects the fronts refused with a message holding each of `words`.
void ExpectFrontsRefused(const std::vector<ParetoFront>& fronts,
                         const std::vector<std::string>& words) {
  const std::string message = ErrorOf([&] { CheckParetoFronts(fronts); });
  ASSERT_FALSE(message.empty()) << "accepted";
  for (const std::string& w : words) EXPECT_NE(message.find(w), std::string::npos) << message;
}

TEST(ParetoFrontsTest, FrontsThatFitPass) {
  EXPECT_NO_THROW(CheckParetoFronts(TwoWindowFronts()));
  EXPECT_NO_THROW(CheckParetoFronts(std::vector{MakeFront("", {{1.0}}, {}, 0, {"weighted sum"})}));
}

TEST(ParetoFrontsTest, FrontsThatDoNotFitAreRefusedNamingTheFront) {
  std::vector<ParetoFront> rows = TwoWindowFronts();
  rows[1].f.conservativeResize(2, Eigen::NoChange);
  ExpectFrontsRefused(rows, {"window 1: scans 120-241", "2 rows", "3 objectives"});

  std::vector<ParetoFront> chosen = TwoWindowFronts();
  chosen[0].chosen = 3;
  ExpectFrontsRefused(chosen, {"window 0", "chosen member 3", "3 members"});

  std::vector<ParetoFront> start = TwoWindowFronts();
  start[1].start.pop_back();
  ExpectFrontsRefused(start, {"window 1", "start has 2 values"});

  std::vector<ParetoFront> infinite = TwoWindowFronts();
  infinite[0].start[2] = std::numeric_limits<double>::infinity();
  ExpectFrontsRefused(infinite, {"window 0", "not finite"});

  std::vector<ParetoFront> names = TwoWindowFronts();
  names[1].objectives[2] = "free cells";
  ExpectFrontsRefused(names, {"window 1", "free cells", "empty cells"});

  std::vector<ParetoFront> fewer = TwoWindowFronts();
  fewer[1] = MakeFront("short", {{1.0, 2.0}}, {}, 0, {"consistency", "occupied cells"});
  ExpectFrontsRefused(fewer, {"short", "objectives"});

  ExpectFrontsRefused({MakeFront("none", {}, {}, 0, {})}, {"none", "no objectives"});
  ExpectFrontsRefused({MakeFront("unnamed", {{1.0, 2.0}}, {}, 0, {"a", ""})},
                      {"unnamed", "no name"});
  ExpectFrontsRefused({MakeFront("empty", {}, {}, 0)}, {"empty", "chosen member 0", "0 members"});
  ExpectFrontsRefused({}, {"none"});
}

TEST(ParetoFrontsTest, NonFiniteObjectiveValuesPass) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  fronts[0].f(1, 2) = std::numeric_limits<double>::quiet_NaN();
  fronts[1].f(0, 0) = -std::numeric_limits<double>::infinity();
  EXPECT_NO_THROW(CheckParetoFronts(fronts));
}

TEST(ParetoFrontsTest, DrawnRelativeOnlyWhenEveryFrontHasAStartWithoutZeros) {
  std::vector<ParetoFront> fronts = TwoWindowFronts();
  EXPECT_TRUE(DrawnRelativeToStart(fronts));
  fronts[1].start[0] = -40.0;
  EXPECT_TRUE(DrawnRelativeToStart(fronts)) << "a negative start scales as well";
  fronts[1].start[0] = 0.0;
  EXPECT_FALSE(DrawnRelativeToStart(fronts));
  fronts = TwoWindowFronts();
  fronts[0].start.clear();
  EXPECT_FALSE(DrawnRelativeToStart(fronts));
}

TEST(ParetoFrontsTest, RelativeValuesAreOneAtTheStartAndLowerWhenBetter) {
  for (const double start : {250.0, -3.0, 1e-3}) {
    EXPECT_DOUBLE_EQ(RelativeToStart(start, start), 1.0);
    EXPECT_LT(RelativeToStart(start - 0.5 * std::abs(start), start), 1.0);
    EXPECT_GT(RelativeToStart(start + 0.5 * std::abs(start), start), 1.0);
    EXPECT_DOUBLE_EQ(RelativeToStart(start - 0.25 * std::abs(start), start), 0.75);
  }
  EXPECT_DOUBLE_EQ(RelativeToStart(200.0, 250.0), 200.0 / 250.0);
}

}  // namespace
}  // namespace evoslam
