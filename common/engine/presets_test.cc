#include "common/engine/presets.h"

#include <gtest/gtest.h>

#include <set>

#include "common/util/error.h"

namespace evoslam {
namespace {

TEST(PresetsTest, EveryPresetBuildsAndStops) {
  std::set<std::string> names;
  for (const Preset& p : Presets()) {
    EXPECT_TRUE(names.insert(p.name).second) << "duplicate " << p.name;
    EXPECT_NO_THROW(MakeAlgorithm(p.algorithm)) << p.name;
    EXPECT_NO_THROW(ValidateStopCriteria(p.stop)) << p.name;
    EXPECT_FALSE(p.source.empty()) << p.name;
  }
}

TEST(PresetsTest, PaperValuesAreThePapers) {
  const Preset& de = FindPreset("de-000");
  EXPECT_EQ(de.algorithm.kind, AlgorithmKind::kDe);
  EXPECT_EQ(de.algorithm.de.strategy, DeStrategy::kRand1Exp);
  EXPECT_EQ(de.algorithm.de.population, 25u);
  EXPECT_EQ(de.stop.max_generations, 25u);
  EXPECT_DOUBLE_EQ(de.algorithm.de.f, 0.6);
  EXPECT_DOUBLE_EQ(de.algorithm.de.cr, 0.9);
  const Preset& global = FindPreset("mu+lambda-002");
  EXPECT_EQ(global.algorithm.mu_plus_lambda.mu, 10u);
  EXPECT_EQ(global.algorithm.mu_plus_lambda.lambda, 70u);
  EXPECT_EQ(global.algorithm.mu_plus_lambda.q, 5u);
  EXPECT_DOUBLE_EQ(global.algorithm.mu_plus_lambda.pm, 0.05);
  EXPECT_DOUBLE_EQ(global.algorithm.mu_plus_lambda.pc, 0.8);
  EXPECT_EQ(global.stop.max_generations, 100u);
  const Preset& immune = FindPreset("immune-004");
  EXPECT_EQ(immune.algorithm.immune.population, 50u);
  EXPECT_DOUBLE_EQ(immune.algorithm.immune.p_immunity, 0.3);
  EXPECT_DOUBLE_EQ(immune.algorithm.immune.p_recombination, 0.9);
  EXPECT_DOUBLE_EQ(immune.algorithm.immune.p_mutation, 0.08);
  EXPECT_EQ(immune.stop.stagnation_generations, 20u);
  const Preset& local = FindPreset("pso-002-local");
  EXPECT_EQ(local.algorithm.pso.particles, 10u);
  EXPECT_DOUBLE_EQ(local.algorithm.pso.c1, 2.0);
  EXPECT_DOUBLE_EQ(local.algorithm.pso.c2, 2.0);
}

TEST(PresetsTest, UnknownNameListsTheValidOnes) {
  try {
    FindPreset("de-999");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("de-000"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace evoslam
