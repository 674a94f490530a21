#include "common/util/finite_checks.h"
#include "common/util/infinity.h"

#include <gtest/gtest.h>

#include <limits>

namespace evoslam {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kTiny = std::numeric_limits<double>::denorm_min();

TEST(FiniteChecksTest, NonNegativeTakesZeroAndFinitePositives) {
  EXPECT_TRUE(IsFiniteNonNegative(0.0));
  EXPECT_TRUE(IsFiniteNonNegative(-0.0));
  EXPECT_TRUE(IsFiniteNonNegative(kTiny));
  EXPECT_TRUE(IsFiniteNonNegative(std::numeric_limits<double>::max()));
  EXPECT_FALSE(IsFiniteNonNegative(-kTiny));
  EXPECT_FALSE(IsFiniteNonNegative(-1.0));
  EXPECT_FALSE(IsFiniteNonNegative(kInfinity));
  EXPECT_FALSE(IsFiniteNonNegative(-kInfinity));
  EXPECT_FALSE(IsFiniteNonNegative(kNan));
  EXPECT_FALSE(IsFiniteNonNegative(-kNan));
}

TEST(FiniteChecksTest, PositiveRefusesZero) {
  EXPECT_TRUE(IsFinitePositive(kTiny));
  EXPECT_TRUE(IsFinitePositive(1.0));
  EXPECT_FALSE(IsFinitePositive(0.0));
  EXPECT_FALSE(IsFinitePositive(-0.0));
  EXPECT_FALSE(IsFinitePositive(-1.0));
  EXPECT_FALSE(IsFinitePositive(kInfinity));
  EXPECT_FALSE(IsFinitePositive(kNan));
}

}  // namespace
}  // namespace evoslam
