#include "common/engine/engine_proto.h"

#include <google/protobuf/stubs/logging.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <string>

#include "common/optim/test_problems.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Every algorithm kind, with non-default parameters so a field dropped on the way shows up.
std::vector<AlgorithmSpec> AllKinds() {
  std::vector<AlgorithmSpec> specs;
  for (const auto& name : AlgorithmKindNames()) {
    AlgorithmSpec s;
    s.kind = ParseAlgorithmKind(name);
    s.de.strategy = DeStrategy::kBest2Bin;
    s.de.population = 13;
    s.de.f = 0.55;
    s.jde.population = 14;
    s.jde.tau_f = 0.2;
    s.pso.particles = 11;
    s.pso.neighbourhood = PsoNeighbourhood::kRing;
    s.ga.population = 17;
    s.ga.crossover = GaCrossover::kUniform;
    s.ga.grid_step = 0.25;
    s.ga.bit_flip = 0.01;
    specs.push_back(s);
  }
  return specs;
}

class EveryAlgorithmTest : public ::testing::TestWithParam<AlgorithmSpec> {};

TEST_P(EveryAlgorithmTest, SettingsRoundTrip) {
  const AlgorithmSpec back = FromProto(ToProto(GetParam()));
  EXPECT_EQ(ToProto(back).SerializeAsString(), ToProto(GetParam()).SerializeAsString());
  EXPECT_EQ(PopulationSize(back), PopulationSize(GetParam()));
}

TEST_P(EveryAlgorithmTest, IslandResumesFromBytesBitForBit) {
  const TestFunctionProblem problem(TestFunction::kRosenbrock, 4);
  StopCriteria stop;
  stop.max_generations = 30;
  Island straight(GetParam(), stop, Rng(5));
  straight.Start(problem);
  straight.Evolve(problem, 100);

  Island first(GetParam(), stop, Rng(5));
  first.Start(problem);
  first.Evolve(problem, 12);
  const std::string bytes = ToProto(first.Checkpoint()).SerializeAsString();
  proto::IslandCheckpoint parsed;
  ASSERT_TRUE(parsed.ParseFromString(bytes));
  Island resumed = Island::FromCheckpoint(FromProto(parsed));
  resumed.Evolve(problem, 100);

  EXPECT_TRUE(resumed.stopped());
  EXPECT_EQ(resumed.stopped(), straight.stopped());
  EXPECT_EQ(resumed.algorithm().population().x, straight.algorithm().population().x);
  EXPECT_EQ(resumed.algorithm().population().f, straight.algorithm().population().f);
  EXPECT_EQ(resumed.algorithm().evaluations(), straight.algorithm().evaluations());
  EXPECT_EQ(resumed.algorithm().champion_x(), straight.algorithm().champion_x());
}

TEST_P(EveryAlgorithmTest, SameBitsWithOneAndTwoThreads) {
  const FunctionProblem problem(Eigen::VectorXd::Constant(6, -3.0),
                                Eigen::VectorXd::Constant(6, 3.0),
                                [](const Eigen::Ref<const Eigen::VectorXd>& x) {
                                  return TestFunctionProblem::Value(TestFunction::kRastrigin, x);
                                });
  const auto run = [&](int threads) {
    omp_set_num_threads(threads);
    StopCriteria stop;
    stop.max_generations = 20;
    Island island(GetParam(), stop, Rng(8));
    island.Start(problem);
    island.Evolve(problem, 100);
    return island.Checkpoint();
  };
  const int saved = omp_get_max_threads();
  const IslandCheckpoint one = run(1);
  const IslandCheckpoint two = run(2);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.state.population.x, two.state.population.x);
  EXPECT_EQ(one.state.population.f, two.state.population.f);
  EXPECT_EQ(one.state.evaluations, two.state.evaluations);
}

INSTANTIATE_TEST_SUITE_P(All, EveryAlgorithmTest, ::testing::ValuesIn(AllKinds()),
                         [](const auto& info) {
                           std::string name(AlgorithmKindName(info.param.kind));
                           std::erase_if(name, [](char c) { return !std::isalnum(c); });
                           return name;
                         });

proto::IslandCheckpoint ValidCheckpoint() {
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  StopCriteria stop;
  stop.max_generations = 5;
  Island island(AlgorithmSpec{}, stop, Rng(1));
  island.Start(problem);
  return ToProto(island.Checkpoint());
}

TEST(EngineProtoTest, RefusesAnotherProtocolVersion) {
  proto::IslandCheckpoint c = ValidCheckpoint();
  c.set_protocol_version(kEngineProtocolVersion + 1);
  try {
    FromProto(c);
    FAIL() << "accepted version " << c.protocol_version();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("protocol version 2"), std::string::npos) << e.what();
  }
}

TEST(EngineProtoTest, RefusesInconsistentShapes) {
  proto::IslandCheckpoint wrong_count = ValidCheckpoint();
  wrong_count.mutable_x()->add_values(1.0);
  EXPECT_THROW(FromProto(wrong_count), Error);

  proto::IslandCheckpoint huge = ValidCheckpoint();
  huge.mutable_x()->set_rows(1u << 30);
  huge.mutable_x()->set_cols(1u << 30);
  EXPECT_THROW(FromProto(huge), Error);

  proto::IslandCheckpoint short_population = ValidCheckpoint();
  short_population.mutable_algorithm()->mutable_de()->set_population(24);
  EXPECT_THROW(FromProto(short_population), Error);

  proto::IslandCheckpoint crowd = ValidCheckpoint();
  crowd.mutable_algorithm()->mutable_de()->set_population(4000000000u);
  EXPECT_THROW(FromProto(crowd), Error);

  proto::IslandCheckpoint no_rng = ValidCheckpoint();
  no_rng.mutable_rng()->clear_words();
  EXPECT_THROW(FromProto(no_rng), Error);

  proto::IslandCheckpoint bad_strategy = ValidCheckpoint();
  bad_strategy.mutable_algorithm()->mutable_de()->set_strategy("rand9bin");
  EXPECT_THROW(FromProto(bad_strategy), Error);

  proto::IslandCheckpoint no_algorithm = ValidCheckpoint();
  no_algorithm.clear_algorithm();
  EXPECT_THROW(FromProto(no_algorithm), Error);

  proto::IslandCheckpoint bad_reason = ValidCheckpoint();
  bad_reason.set_stop_reason("bored");
  EXPECT_THROW(FromProto(bad_reason), Error);
}

TEST(EngineProtoTest, RandomBytesNeverCrash) {
  // Protobuf logs each invalid UTF-8 string it meets; the refusals are what is tested here.
  const google::protobuf::LogSilencer quiet;
  Rng rng(99);
  const std::string valid = ValidCheckpoint().SerializeAsString();
  int refused = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bytes = valid;
    // Flip a few bytes of a valid message, or make one up from nothing.
    if (trial % 2 == 0) {
      for (int k = 0; k < 4; ++k)
        bytes[rng.UniformIndex(bytes.size())] = static_cast<char>(rng.NextU64());
    } else {
      bytes.resize(rng.UniformIndex(200));
      for (char& c : bytes) c = static_cast<char>(rng.NextU64());
    }
    proto::IslandCheckpoint parsed;
    if (!parsed.ParseFromString(bytes)) {
      ++refused;
      continue;
    }
    try {
      FromProto(parsed);
    } catch (const Error&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 1000);
}

}  // namespace
}  // namespace evoslam
