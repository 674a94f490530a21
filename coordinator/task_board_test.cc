#include "coordinator/task_board.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <thread>

namespace evoslam {
namespace {

proto::Task TaskWithScan(std::uint32_t scan) {
  proto::Task t;
  t.mutable_problem()->set_scan(scan);
  return t;
}

proto::TaskResult Answer(const proto::Task& task, double value) {
  proto::TaskResult r;
  r.set_task_id(task.task_id());
  r.mutable_fitness()->set_rows(1);
  r.mutable_fitness()->set_cols(1);
  r.mutable_fitness()->add_values(value);
  return r;
}

// Takes a task from the board, waiting for the poster to have posted it.
proto::Task TakeSoon(TaskBoard& board) {
  for (int i = 0; i < 2000; ++i) {
    if (auto t = board.Take()) return *t;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ADD_FAILURE() << "no task was posted";
  return {};
}

TEST(TaskBoardTest, ResultsComeBackInTheOrderPostedWhateverOrderTheyArrive) {
  std::atomic<int> wakes{0};
  TaskBoard board([&] { ++wakes; });
  auto results = std::async(std::launch::async, [&] {
    return board.RunAll("job-1", {TaskWithScan(0), TaskWithScan(1), TaskWithScan(2)});
  });
  const proto::Task a = TakeSoon(board), b = TakeSoon(board), c = TakeSoon(board);
  EXPECT_EQ(a.problem().scan(), 0u);  // oldest first
  EXPECT_EQ(c.problem().scan(), 2u);
  EXPECT_EQ(a.job_id(), "job-1");
  EXPECT_NE(a.task_id(), b.task_id());
  EXPECT_TRUE(board.Complete(Answer(c, 2.0)));
  EXPECT_TRUE(board.Complete(Answer(a, 0.0)));
  EXPECT_FALSE(board.Complete(Answer(a, 9.0)));  // a second answer is a straggler's
  EXPECT_TRUE(board.Complete(Answer(b, 1.0)));
  const auto r = results.get();
  ASSERT_EQ(r.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r[i].fitness().values(0), i);
  EXPECT_GE(wakes.load(), 1);
  EXPECT_FALSE(board.Complete(Answer(b, 1.0)));  // collected: nobody waits any more
}

TEST(TaskBoardTest, ARequeuedTaskGoesBackToTheFrontOfTheLine) {
  TaskBoard board({});
  auto results = std::async(std::launch::async, [&] {
    return board.RunAll("job-1", {TaskWithScan(0), TaskWithScan(1)});
  });
  const proto::Task first = TakeSoon(board);
  board.Requeue(first.task_id());
  const proto::Task again = TakeSoon(board);
  EXPECT_EQ(again.task_id(), first.task_id());
  const proto::Task second = TakeSoon(board);
  EXPECT_EQ(second.problem().scan(), 1u);
  EXPECT_FALSE(board.Take());
  board.Complete(Answer(first, 0.0));
  board.Requeue(first.task_id());  // already answered: stays out of the line
  EXPECT_FALSE(board.Take());
  board.Complete(Answer(second, 1.0));
  EXPECT_EQ(results.get().size(), 2u);
}

TEST(TaskBoardTest, ATaskThatLosesEveryWorkerItReachesFailsItsJob) {
  TaskBoard board({}, 2);
  auto results =
      std::async(std::launch::async, [&] { return board.RunAll("job-1", {TaskWithScan(0)}); });
  const proto::Task t = TakeSoon(board);
  board.Requeue(t.task_id());  // second attempt
  EXPECT_EQ(TakeSoon(board).task_id(), t.task_id());
  board.Requeue(t.task_id());  // a third would be one too many
  EXPECT_FALSE(board.Take());
  try {
    results.get();
    FAIL() << "the job must fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lost its worker 2 times"), std::string::npos);
  }
}

TEST(TaskBoardTest, CancellingAJobWakesItsThreadAndDropsItsTasks) {
  TaskBoard board({});
  auto cancelled = std::async(std::launch::async, [&] {
    return board.RunAll("job-1", {TaskWithScan(0), TaskWithScan(1)});
  });
  const proto::Task taken = TakeSoon(board);  // job-1's first task, now "at a worker"
  auto other =
      std::async(std::launch::async, [&] { return board.RunAll("job-2", {TaskWithScan(7)}); });
  while (board.waiting() < 2) std::this_thread::yield();
  board.Cancel("job-1");
  EXPECT_THROW(cancelled.get(), JobInterrupted);
  EXPECT_FALSE(board.Complete(Answer(taken, 0.0)));  // its answer is dropped
  // Only job-2's task is left waiting.
  const std::optional<proto::Task> left = board.Take();
  ASSERT_TRUE(left);
  EXPECT_EQ(left->job_id(), "job-2");
  EXPECT_FALSE(board.Take());
  board.Complete(Answer(*left, 7.0));
  EXPECT_EQ(other.get().front().fitness().values(0), 7.0);
  EXPECT_THROW(board.RunAll("job-1", {TaskWithScan(0)}), JobInterrupted);
}

TEST(TaskBoardTest, AFailedTaskIsAnErrorForItsJobAndShutdownInterruptsEveryone) {
  TaskBoard board({});
  auto failing =
      std::async(std::launch::async, [&] { return board.RunAll("job-1", {TaskWithScan(0)}); });
  const proto::Task t = TakeSoon(board);
  proto::TaskResult failed;
  failed.set_task_id(t.task_id());
  failed.mutable_error()->set_message("scan 0 is not in the log");
  board.Complete(failed);
  try {
    failing.get();
    FAIL() << "a failed task must fail its job";
  } catch (const JobInterrupted&) {
    FAIL() << "a failure is not an interruption";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scan 0 is not in the log"), std::string::npos);
  }
  auto waiting =
      std::async(std::launch::async, [&] { return board.RunAll("job-2", {TaskWithScan(0)}); });
  TakeSoon(board);
  board.Shutdown();
  EXPECT_THROW(waiting.get(), JobInterrupted);
  EXPECT_THROW(board.RunAll("job-3", {TaskWithScan(0)}), JobInterrupted);
}

// A job thread computing between tasks (a SLAM job's local search) learns it should stop.
TEST(TaskBoardTest, AJobThreadBetweenTasksCanAskWhetherToStop) {
  TaskBoard board({});
  EXPECT_NO_THROW(board.ThrowIfInterrupted("job-1"));
  board.Cancel("job-1");
  EXPECT_THROW(board.ThrowIfInterrupted("job-1"), JobInterrupted);
  EXPECT_NO_THROW(board.ThrowIfInterrupted("job-2"));
  board.Shutdown();
  EXPECT_THROW(board.ThrowIfInterrupted("job-2"), JobInterrupted);
}

// A task whose worker failed through no fault of the task's goes back as often as it takes; a
// task that loses its workers runs out of attempts.
TEST(TaskBoardTest, AReturnedTaskCountsNoAttempt) {
  TaskBoard board({}, 2);
  auto results =
      std::async(std::launch::async, [&] { return board.RunAll("job-1", {TaskWithScan(0)}); });
  proto::Task task = TakeSoon(board);
  for (int i = 0; i < 10; ++i) {
    board.Return(task.task_id());
    board.Return(task.task_id());  // once in the line, however often it is returned
    task = TakeSoon(board);
    EXPECT_FALSE(board.Take());
  }
  board.Requeue(task.task_id());  // attempt 2 of 2
  task = TakeSoon(board);
  board.Requeue(task.task_id());
  EXPECT_FALSE(board.Take());
  EXPECT_THROW(results.get(), Error);
}

TEST(TaskBoardTest, AnEchoedIslandIsInvalidAndAnAnswerToNoWaitingTaskIsNotChecked) {
  TaskBoard board({});
  proto::Task island;
  island.mutable_evolve()->set_generations(5);
  island.mutable_evolve()->mutable_island()->set_generation(3);
  auto results = std::async(std::launch::async, [&] { return board.RunAll("job-1", {island}); });
  const proto::Task task = TakeSoon(board);
  proto::TaskResult echo;
  echo.set_task_id(task.task_id());
  *echo.mutable_island()->mutable_island() = task.evolve().island();
  EXPECT_TRUE(board.Check(echo));
  echo.set_task_id("t-999");
  EXPECT_FALSE(board.Check(echo));
  board.Cancel("job-1");
  EXPECT_THROW(results.get(), JobInterrupted);
}

}  // namespace
}  // namespace evoslam
