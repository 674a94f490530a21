#include "common/io/text_fields.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace evoslam {
namespace {

using ::testing::ElementsAre;

TEST(TextFieldsTest, SplitsOnRunsOfSpacesAndTabs) {
  std::vector<std::string_view> fields = {"stale"};
  SplitFields("  FLASER\t3  1.0 2 \r", &fields);
  EXPECT_THAT(fields, ElementsAre("FLASER", "3", "1.0", "2"));
  SplitFields("   ", &fields);
  EXPECT_TRUE(fields.empty());
}

TEST(TextFieldsTest, StripsFromTheFirstHash) {
  EXPECT_EQ(StripHashComment("1 2 # a # b"), "1 2 ");
  EXPECT_EQ(StripHashComment("#all"), "");
  EXPECT_EQ(StripHashComment("no comment"), "no comment");
}

TEST(TextFieldsTest, ParsesWholeNumbersOnly) {
  EXPECT_EQ(ParseDouble("976052905.167303"), 976052905.167303);
  EXPECT_EQ(ParseDouble("-1.5e-3"), -1.5e-3);
  EXPECT_EQ(ParseDouble("+2.5"), 2.5);
  EXPECT_FALSE(ParseDouble(""));
  EXPECT_FALSE(ParseDouble("1.5x"));
  EXPECT_FALSE(ParseDouble("x"));
  EXPECT_FALSE(ParseDouble("+-1"));
  EXPECT_FALSE(ParseDouble("1e999"));
  EXPECT_TRUE(std::isnan(*ParseDouble("nan")));
  EXPECT_TRUE(std::isinf(*ParseDouble("inf")));
  EXPECT_EQ(ParseFloat("1.07"), 1.07F);
  EXPECT_EQ(ParseCount("180"), 180u);
  EXPECT_FALSE(ParseCount("-1"));
  EXPECT_FALSE(ParseCount("1.5"));
  EXPECT_FALSE(ParseCount("99999999999999999999999"));
}

TEST(TextFieldsTest, FormatsTheShortestTextThatReadsBack) {
  EXPECT_EQ(FormatShortest(0.05), "0.05");
  EXPECT_EQ(FormatShortest(8.0), "8");
  EXPECT_EQ(FormatShortest(-1e-300), "-1e-300");
  for (const double v : {0.1 + 0.2, 976052905.167303, -2.2250738585072014e-308, 1.0 / 3.0}) {
    EXPECT_EQ(ParseDouble(FormatShortest(v)), v) << FormatShortest(v);
  }
}

}  // namespace
}  // namespace evoslam
