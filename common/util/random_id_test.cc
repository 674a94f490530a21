#include "common/util/random_id.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace evoslam {
namespace {

TEST(RandomHexIdTest, IsLowercaseHexOfTwiceTheBytes) {
  for (const std::size_t bytes : {0u, 1u, 16u, 33u}) {
    const std::string id = RandomHexId(bytes);
    EXPECT_EQ(id.size(), 2 * bytes) << id;
    EXPECT_EQ(id.find_first_not_of("0123456789abcdef"), std::string::npos) << id;
  }
}

// Drawn from the system's CSPRNG, not a seeded stream: no two draws repeat.
TEST(RandomHexIdTest, NeverRepeats) {
  std::set<std::string> ids;
  for (int i = 0; i < 1000; ++i) EXPECT_TRUE(ids.insert(RandomHexId(16)).second);
}

}  // namespace
}  // namespace evoslam
