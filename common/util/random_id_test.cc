#include "common/util/random_id.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace evoslam {
namespace {

TEST(RandomIdTest, IsThePrefixAnd32HexDigits) {
  const std::string id = RandomId("upload-");
  ASSERT_EQ(id.size(), 7u + 32u);
  EXPECT_EQ(id.substr(0, 7), "upload-");
  EXPECT_EQ(id.substr(7).find_first_not_of("0123456789abcdef"), std::string::npos) << id;
}

TEST(RandomIdTest, NeverRepeats) {
  std::set<std::string> ids;
  for (int i = 0; i < 10000; ++i) ids.insert(RandomId(""));
  EXPECT_EQ(ids.size(), 10000u);
}

}  // namespace
}  // namespace evoslam
