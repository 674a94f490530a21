#include "common/slam/memory_need.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/util/error.h"

namespace evoslam {
namespace {

using ::testing::HasSubstr;

const MemoryNeed kNeed{.bytes = 1'400'000'000, .driver = "its map of 4 x 4 cells (--resolution)"};

TEST(CheckMemoryNeedTest, ARunOverWhatIsAvailableIsRefusedWithBothFiguresAndTheCause) {
  try {
    CheckMemoryNeed(kNeed, 900'000'000);
    ADD_FAILURE() << "a run needing more than there is was let through";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("about 1.4 GB"));
    EXPECT_THAT(e.what(), HasSubstr("900 MB available"));
    EXPECT_THAT(e.what(), HasSubstr("its map of 4 x 4 cells (--resolution)"));
  }
}

TEST(CheckMemoryNeedTest, ARunOverAGigabyteThatFitsIsAnnounced) {
  const auto warning = CheckMemoryNeed(kNeed, 2'000'000'000);
  ASSERT_TRUE(warning);
  EXPECT_THAT(*warning, HasSubstr("about 1.4 GB"));
  EXPECT_THAT(*warning, HasSubstr("--resolution"));
  // Unknown availability refuses nothing.
  EXPECT_TRUE(CheckMemoryNeed(kNeed, std::nullopt));
}

TEST(CheckMemoryNeedTest, ASmallRunSaysNothing) {
  EXPECT_EQ(CheckMemoryNeed({.bytes = kLargeRunBytes, .driver = "x"}, kLargeRunBytes),
            std::nullopt);
}

}  // namespace
}  // namespace evoslam
