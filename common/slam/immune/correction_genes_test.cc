#include "common/slam/immune/correction_genes.h"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

namespace evoslam {
namespace {

TEST(CorrectionGenesTest, IntegerGenesAreWholeUnitsWithin004sBounds) {
  const CorrectionGenes genes(proto::TrajectorySegmentParams(), 3, 2);
  ASSERT_EQ(genes.dimension(), 10u);
  EXPECT_EQ(genes.encoding(), Encoding::kInteger);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_EQ(genes.lower()[static_cast<Eigen::Index>(2 * j)], -20.0);  // cm
    EXPECT_EQ(genes.upper()[static_cast<Eigen::Index>(2 * j)], 20.0);
    EXPECT_EQ(genes.lower()[static_cast<Eigen::Index>(2 * j + 1)], -10.0);  // degrees
    EXPECT_EQ(genes.upper()[static_cast<Eigen::Index>(2 * j + 1)], 10.0);
  }
  for (Eigen::Index g = 6; g < 10; ++g) {  // key point offsets, in cells
    EXPECT_EQ(genes.lower()[g], -1.0);
    EXPECT_EQ(genes.upper()[g], 1.0);
  }
}

TEST(CorrectionGenesTest, GenesDecodeToMetresAndRadians) {
  const CorrectionGenes genes(proto::TrajectorySegmentParams(), 2, 1);
  Eigen::VectorXd x(6);
  x << 5, -3, -20, 10, 1, -1;
  std::vector<SegmentCorrection> c(2);
  genes.Corrections(x, c);
  EXPECT_DOUBLE_EQ(c[0].length, 0.05);
  EXPECT_DOUBLE_EQ(c[0].turn, -3 * std::numbers::pi / 180);
  EXPECT_DOUBLE_EQ(c[1].length, -0.2);
  EXPECT_DOUBLE_EQ(c[1].turn, 10 * std::numbers::pi / 180);
  EXPECT_EQ(genes.KeyPointOffset(x, 0), Eigen::Vector2d(1, -1));
  EXPECT_EQ(CorrectionGenes::LengthGene(1), 2u);
}

TEST(CorrectionGenesTest, ContinuousGenesKeepBoundsThatAreNoWholeUnit) {
  proto::TrajectorySegmentParams params;
  params.set_encoding("continuous");
  params.set_max_length_correction_m(0.155);
  const CorrectionGenes genes(params, 1, 0);
  EXPECT_EQ(genes.encoding(), Encoding::kReal);
  EXPECT_NEAR(genes.upper()[0], 15.5, 1e-12);
  params.set_encoding("integer");
  EXPECT_EQ(CorrectionGenes(params, 1, 0).upper()[0], 15.0);
}

}  // namespace
}  // namespace evoslam
