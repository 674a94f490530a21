#include "common/util/nearest_name.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace evoslam {
namespace {

TEST(EditDistanceTest, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("slam", "slam"), 0u);
  EXPECT_EQ(EditDistance("slm", "slam"), 1u);
  EXPECT_EQ(EditDistance("slaam", "slam"), 1u);
  EXPECT_EQ(EditDistance("slum", "slam"), 1u);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("inof", "info"), 1u);
  EXPECT_EQ(EditDistance("ab", "ba"), 1u);
  EXPECT_EQ(EditDistance("", "info"), 4u);
  EXPECT_EQ(EditDistance("abc", "cba"), EditDistance("cba", "abc"));
}

TEST(NearestNameTest, SuggestsTheClosestNameWithinReach) {
  const std::vector<std::string> names = {"info", "simulate", "slam", "localize", "eval"};
  EXPECT_EQ(NearestName("slm", names), "slam");
  EXPECT_EQ(NearestName("localise", names), "localize");
  EXPECT_EQ(NearestName("simualte", names), "simulate");
  EXPECT_EQ(NearestName("inof", names), "info");
}

TEST(NearestNameTest, SuggestsTheOnlyNameThatStartsWithIt) {
  const std::vector<std::string> worlds = {"office-boxes", "office-cluster", "s-corridor",
                                           "empty-room"};
  EXPECT_EQ(NearestName("office-c", worlds), "office-cluster");
  EXPECT_EQ(NearestName("empty", worlds), "empty-room");
  EXPECT_FALSE(NearestName("office", worlds)) << "two names start with it";
}

TEST(NearestNameTest, SuggestsNothingForANameFarFromEvery) {
  const std::vector<std::string> names = {"info", "slam"};
  EXPECT_FALSE(NearestName("compile", names));
  EXPECT_FALSE(NearestName("xyz", names));
  EXPECT_FALSE(NearestName("", names));
}

}  // namespace
}  // namespace evoslam
