#include "common/engine/island.h"

#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "common/engine/archipelago.h"
#include "common/engine/engine_proto.h"
#include "common/engine/presets.h"
#include "common/optim/test_problems.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// An island through its wire form and back, as the service ships it to a worker.
Island Shipped(const Island& island) {
  std::string bytes;
  EXPECT_TRUE(ToProto(island.Checkpoint()).SerializeToString(&bytes));
  proto::IslandCheckpoint parsed;
  EXPECT_TRUE(parsed.ParseFromString(bytes));
  return Island::FromCheckpoint(FromProto(parsed));
}

class ShippedIslandTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedIslandTest, AnIslandShippedBeforeItsFirstGenerationRunsAsIfItNeverLeft) {
  const Preset& preset = FindPreset(GetParam());
  const TestFunctionProblem single(TestFunction::kRastrigin, 2);
  const ZdtProblem multi(1, 4);
  const bool multi_objective = MakeAlgorithm(preset.algorithm)->multi_objective();
  const Problem& problem = multi_objective ? static_cast<const Problem&>(multi) : single;
  StopCriteria stop;
  stop.max_generations = 6;

  Island here(preset.algorithm, stop, Rng(11));
  Island away = Shipped(Island(preset.algorithm, stop, Rng(11)));
  here.Start(problem);
  here.Evolve(problem, 3);
  away.Start(problem);
  away = Shipped(away);
  away.Evolve(problem, 3);
  EXPECT_EQ(away.algorithm().population().x, here.algorithm().population().x);
  EXPECT_EQ(away.algorithm().population().f, here.algorithm().population().f);
  EXPECT_EQ(away.algorithm().evaluations(), here.algorithm().evaluations());
}

INSTANTIATE_TEST_SUITE_P(EveryPreset, ShippedIslandTest, ::testing::ValuesIn(PresetNames()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(IslandTest, AnIslandOfAnotherProblemIsRefusedBeforeItEvolves) {
  StopCriteria stop;
  stop.max_generations = 6;
  Island island(FindPreset("de-000").algorithm, stop, Rng(3));
  island.Start(TestFunctionProblem(TestFunction::kSphere, 3));
  Island restored = Island::FromCheckpoint(island.Checkpoint());
  try {
    restored.Evolve(TestFunctionProblem(TestFunction::kSphere, 5), 2);
    ADD_FAILURE() << "an island of 3 coordinates evolved on a problem of 5";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3 coordinates for a problem of 5"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(restored.Evolve(TestFunctionProblem(TestFunction::kSphere, 3), 2).has_value());
}

// The coordinator's scheme: every epoch the islands travel to workers as checkpoints and come
// back; the archipelago migrates between them as it does in one process.
TEST(ShippedArchipelagoTest, AnArchipelagoWhoseIslandsTravelEveryEpochMatchesOneThatStaysHome) {
  const TestFunctionProblem problem(TestFunction::kRastrigin, 6);
  IslandModelParams params;
  params.islands = 3;
  params.algorithm = FindPreset("de-000").algorithm;
  params.migration.interval = 4;
  params.migration.migrants = 2;
  params.migration.topology = Topology::kRandom;
  StopCriteria stop;
  stop.max_generations = 20;

  Archipelago home(params, stop, 5);
  home.Run(problem);

  Archipelago travelling(params, stop, 5);
  const IslandStepper remote = [&](std::vector<Island>& islands, bool start,
                                   std::size_t generations) {
    for (Island& island : islands) {
      Island worker = Shipped(island);
      if (start) worker.Start(problem);
      if (generations > 0) worker.Evolve(problem, generations);
      island = Shipped(worker);
    }
  };
  travelling.Start(remote);
  while (!travelling.RunEpoch(remote)) {
  }
  EXPECT_EQ(travelling.epoch(), home.epoch());
  EXPECT_EQ(travelling.Merged().x, home.Merged().x);
  EXPECT_EQ(travelling.Best().best_fitness, home.Best().best_fitness);
}

}  // namespace
}  // namespace evoslam
