#include "coordinator/result_check.h"

#include <gtest/gtest.h>

#include <limits>

#include "common/engine/engine_proto.h"
#include "common/engine/island.h"
#include "common/optim/test_problems.h"

namespace evoslam {
namespace {

// An island task as a job's thread posts it, and the answer a worker that ran it gives.
struct IslandTask {
  proto::Task task;
  proto::TaskResult answer;
};

IslandTask EvolvedIsland(bool start, std::uint64_t generations) {
  const TestFunctionProblem problem(TestFunction::kSphere, 3);
  Island island(AlgorithmSpec{}, StopCriteria{}, Rng(1));
  if (!start) island.Start(problem);
  IslandTask t;
  t.task.set_task_id("t-1");
  proto::EvolveIsland& evolve = *t.task.mutable_evolve();
  *evolve.mutable_island() = ToProto(island.Checkpoint());
  evolve.set_start(start);
  evolve.set_generations(generations);
  if (start) island.Start(problem);
  island.Evolve(problem, generations);
  t.answer.set_task_id("t-1");
  *t.answer.mutable_island()->mutable_island() = ToProto(island.Checkpoint());
  return t;
}

TEST(ResultCheckTest, AnIslandThatAdvancedAsAskedIsTaken) {
  for (const bool start : {true, false}) {
    for (const std::uint64_t generations : {0u, 4u}) {
      if (!start && generations == 0) continue;  // nothing asked, nothing to check
      const IslandTask t = EvolvedIsland(start, generations);
      EXPECT_EQ(CheckResult(t.task, t.answer), std::nullopt)
          << "start " << start << ", " << generations << " generations";
    }
  }
}

TEST(ResultCheckTest, AnEchoedOrMadeUpIslandIsRefused) {
  IslandTask t = EvolvedIsland(false, 4);
  proto::TaskResult echo;
  echo.set_task_id("t-1");
  *echo.mutable_island()->mutable_island() = t.task.evolve().island();
  EXPECT_TRUE(CheckResult(t.task, echo));

  // The first population of a start task echoed: nothing was drawn.
  const IslandTask s = EvolvedIsland(true, 0);
  *echo.mutable_island()->mutable_island() = s.task.evolve().island();
  EXPECT_TRUE(CheckResult(s.task, echo));

  proto::TaskResult bad = t.answer;
  bad.mutable_island()->mutable_island()->mutable_f()->set_values(
      0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(CheckResult(t.task, bad)) << "a NaN fitness";

  bad = t.answer;
  bad.mutable_island()->mutable_island()->set_generation(t.answer.island().island().generation() +
                                                         1);
  EXPECT_TRUE(CheckResult(t.task, bad)) << "more generations than asked";

  bad = t.answer;
  proto::Matrix& x = *bad.mutable_island()->mutable_island()->mutable_x();
  x.set_rows(x.rows() - 1);
  x.mutable_values()->Truncate(static_cast<int>(x.rows() * x.cols()));
  EXPECT_TRUE(CheckResult(t.task, bad)) << "a candidate of the wrong dimension";

  bad = t.answer;
  bad.set_task_id("t-2");
  EXPECT_TRUE(CheckResult(t.task, bad)) << "another task's id";

  bad.Clear();
  bad.set_task_id("t-1");
  bad.mutable_fitness()->set_rows(1);
  EXPECT_TRUE(CheckResult(t.task, bad)) << "a batch's answer to an island task";
}

TEST(ResultCheckTest, ABatchNeedsOneFiniteFitnessPerCandidate) {
  proto::Task task;
  task.set_task_id("t-1");
  proto::Matrix& candidates = *task.mutable_evaluate()->mutable_candidates();
  task.mutable_evaluate()->set_objectives(1);
  candidates.set_rows(3);
  candidates.set_cols(2);
  for (int i = 0; i < 6; ++i) candidates.add_values(i);
  proto::TaskResult answer;
  answer.set_task_id("t-1");
  answer.mutable_fitness()->set_rows(1);
  answer.mutable_fitness()->set_cols(2);
  answer.mutable_fitness()->add_values(1.0);
  answer.mutable_fitness()->add_values(2.0);
  EXPECT_EQ(CheckResult(task, answer), std::nullopt);

  proto::TaskResult echo = answer;
  *echo.mutable_fitness() = candidates;
  EXPECT_TRUE(CheckResult(task, echo));
  proto::TaskResult short_answer = answer;
  short_answer.mutable_fitness()->set_cols(1);
  short_answer.mutable_fitness()->mutable_values()->RemoveLast();
  EXPECT_TRUE(CheckResult(task, short_answer));
  answer.mutable_fitness()->set_values(1, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(CheckResult(task, answer));

  // An error is an answer too: whose fault it is, the coordinator decides elsewhere.
  proto::TaskResult error;
  error.set_task_id("t-1");
  error.mutable_error()->set_message("bad input");
  EXPECT_EQ(CheckResult(task, error), std::nullopt);
}

}  // namespace
}  // namespace evoslam
