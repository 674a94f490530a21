#include "common/util/error.h"

#include <gtest/gtest.h>

#include <string>

namespace evoslam {
namespace {

TEST(InputErrorTest, NamesFileAndLine) {
  const InputError e("maps/office.lines", 12, "expected 4 numbers");
  EXPECT_EQ(std::string(e.what()), "maps/office.lines:12: expected 4 numbers");
  EXPECT_EQ(e.source(), "maps/office.lines");
  EXPECT_EQ(e.line(), 12u);
}

TEST(InputErrorTest, LineZeroMeansTheWholeFile) {
  const InputError e("log.clf.xz", 0, "unknown compression");
  EXPECT_EQ(std::string(e.what()), "log.clf.xz: unknown compression");
}

TEST(InputErrorTest, IsAnError) { EXPECT_THROW(throw InputError("f", 1, "m"), Error); }

}  // namespace
}  // namespace evoslam
