#include "common/util/counted.h"

#include <gtest/gtest.h>

namespace evoslam {
namespace {

TEST(CountedTest, TheNounIsPluralUnlessTheCountIsOne) {
  EXPECT_EQ(Counted(0, "thread"), "0 threads");
  EXPECT_EQ(Counted(1, "thread"), "1 thread");
  EXPECT_EQ(Counted(2, "worker"), "2 workers");
  EXPECT_EQ(Counted(1000, "scan"), "1000 scans");
}

}  // namespace
}  // namespace evoslam
