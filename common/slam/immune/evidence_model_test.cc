#include "common/slam/immune/evidence_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

// Dempster's rule as written, in doubles, for sums small enough that it is safe.
CellBeliefs Direct(double occupied_nats, double empty_nats) {
  const double occ = 1.0 - std::exp(-occupied_nats);
  const double emp = 1.0 - std::exp(-empty_nats);
  const double k = occ * emp;
  return {occ * (1 - emp) / (1 - k), emp * (1 - occ) / (1 - k)};
}

TEST(EvidenceModelTest, BeliefsFollowDempstersRule) {
  const EvidenceScorer scorer(0.5);
  for (const auto& [a, b] : {std::pair{0u, 0u},
                             {3000u, 0u},
                             {0u, 2500u},
                             {3000u, 1500u},
                             {700u, 9000u},
                             {20000u, 20000u},
                             {1u, 2u}}) {
    const CellBeliefs got = scorer.Beliefs(a, b);
    const CellBeliefs want = Direct(a * kEvidenceUnit, b * kEvidenceUnit);
    EXPECT_NEAR(got.occupied, want.occupied, 1e-12) << a << " " << b;
    EXPECT_NEAR(got.empty, want.empty, 1e-12) << a << " " << b;
    if ((a | b) == 0) continue;
    const double contradiction = std::min(want.occupied, want.empty);
    EXPECT_NEAR(scorer.Score(a, b).consistency * kConsistencyUnit, contradiction, 1e-9)
        << a << " " << b;
  }
}

TEST(EvidenceModelTest, CellWithoutEvidenceScoresNothing) {
  const CellScore s = EvidenceScorer(0.5).Score(0, 0);
  EXPECT_EQ(s.consistency, 0);
  EXPECT_FALSE(s.occupied);
  EXPECT_FALSE(s.empty);
}

TEST(EvidenceModelTest, HugeSumsStayFinite) {
  const EvidenceScorer scorer(0.5);
  const std::uint32_t most = std::numeric_limits<std::uint32_t>::max();
  // Both certain: the conflict splits the belief evenly, each side half.
  const CellBeliefs even = scorer.Beliefs(most, most);
  EXPECT_DOUBLE_EQ(even.occupied, 0.5);
  EXPECT_DOUBLE_EQ(even.empty, 0.5);
  EXPECT_EQ(scorer.Score(most, most).consistency * kConsistencyUnit, 0.5);
  // One certain, the other strong: the certain side wins outright.
  const CellBeliefs one = scorer.Beliefs(most, 200000);
  EXPECT_DOUBLE_EQ(one.occupied, 1.0);
  EXPECT_EQ(one.empty, 0.0);
  EXPECT_EQ(scorer.Score(most, 200000).consistency, 0);
  EXPECT_TRUE(scorer.Score(most, 200000).occupied);
  for (const std::uint32_t b : {0u, 1u, 100000u, most}) {
    const CellBeliefs c = scorer.Beliefs(most - 1, b);
    EXPECT_TRUE(std::isfinite(c.occupied) && std::isfinite(c.empty)) << b;
  }
}

TEST(EvidenceModelTest, UnitsOfAReadingAreRoundedAndNeverZero) {
  EXPECT_EQ(EvidenceUnits(0.5), static_cast<std::uint32_t>(std::round(std::log(2.0) * 4096)));
  EXPECT_EQ(EvidenceUnits(1e-12), 1u);
  proto::EvidenceGridParams params;
  EXPECT_DOUBLE_EQ(ReadingMass(params, 0.0), params.max_belief());
  EXPECT_DOUBLE_EQ(ReadingMass(params, 1.0), params.max_belief() / std::exp(1.0));
  const EmptyWeights weights(params, 0.05);
  EXPECT_GT(weights.at(0.0), weights.at(30.0));
  EXPECT_EQ(weights.at(60.0), weights.at(1e9));  // clamped past the maximum range
}

TEST(EvidenceModelTest, ValidationNamesTheFirstBadField) {
  const auto message = [](const proto::EvidenceGridParams& p) -> std::string {
    try {
      ValidateEvidenceGridParams(p);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message(proto::EvidenceGridParams()), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  proto::EvidenceGridParams p;
  for (const double bad : {0.0, -0.05, nan}) {
    p = {};
    p.set_cell_size_m(bad);
    EXPECT_NE(message(p).find("evidence.cell_size_m"), std::string::npos) << bad;
  }
  p = {};
  p.set_max_range_m(0.0);
  EXPECT_NE(message(p).find("evidence.max_range_m"), std::string::npos);
  p = {};
  p.set_max_range_m(1e6);
  EXPECT_NE(message(p).find("evidence.max_range_m"), std::string::npos);
  for (const double bad : {0.0, 1.0, -0.1, nan}) {
    p = {};
    p.set_max_belief(bad);
    EXPECT_NE(message(p).find("evidence.max_belief"), std::string::npos) << bad;
  }
  p = {};
  p.set_reliability_distance_m(-1.0);
  EXPECT_NE(message(p).find("evidence.reliability_distance_m"), std::string::npos);
  for (const double bad : {-0.1, 1.0, nan}) {
    p = {};
    p.set_count_above(bad);
    EXPECT_NE(message(p).find("evidence.count_above"), std::string::npos) << bad;
  }
  p = {};
  p.set_beam_stride(0);
  EXPECT_NE(message(p).find("evidence.beam_stride"), std::string::npos);
  // The first bad field is named.
  p = {};
  p.set_cell_size_m(0.0);
  p.set_beam_stride(0);
  EXPECT_NE(message(p).find("evidence.cell_size_m"), std::string::npos);
}

}  // namespace
}  // namespace evoslam
