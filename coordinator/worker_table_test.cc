#include "coordinator/worker_table.h"

#include <gtest/gtest.h>

namespace evoslam {
namespace {

using Clock = WorkerTable::Clock;

proto::Ready ReadyWith(std::uint32_t threads) {
  proto::Ready r;
  r.set_hostname("host");
  r.set_threads(threads);
  return r;
}

TEST(WorkerTableTest, WorkGoesToTheWorkerIdleLongestAndBusyWorkersGetNone) {
  WorkerTable table;
  const Clock::time_point t0 = Clock::now();
  table.Ready("a", ReadyWith(2), t0);
  table.Ready("b", ReadyWith(1), t0);
  EXPECT_EQ(table.threads(), 3u);
  EXPECT_EQ(table.Assign("t-1", t0 + std::chrono::seconds(10)), "a");
  EXPECT_EQ(table.Assign("t-2", t0 + std::chrono::seconds(10)), "b");
  EXPECT_FALSE(table.Assign("t-3", t0));
  EXPECT_EQ(table.TaskOf("a"), "t-1");
  table.Done("b");
  table.Done("a");
  EXPECT_EQ(table.Assign("t-3", t0), "b");  // b has been idle longer
  const auto list = table.List(t0, 1000.0);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_NE(list[0].worker_id(), list[1].worker_id());
}

TEST(WorkerTableTest, SilentAndOverdueWorkersAreLostAndGiveBackTheirTasks) {
  WorkerTable table;
  const Clock::time_point t0 = Clock::now();
  table.Ready("quiet", ReadyWith(1), t0);
  table.Ready("slow", ReadyWith(1), t0);
  table.Ready("fine", ReadyWith(1), t0);
  table.Assign("t-1", t0 + std::chrono::seconds(100));  // quiet
  table.Assign("t-2", t0 + std::chrono::seconds(1));    // slow
  const Clock::time_point t5 = t0 + std::chrono::seconds(5);
  table.Seen("slow", t5);
  table.Seen("fine", t5);
  auto lost = table.Lost(t5, t5 - std::chrono::seconds(3));
  std::sort(lost.begin(), lost.end());
  EXPECT_EQ(lost, (std::vector<std::string>{"quiet", "slow"}));
  EXPECT_EQ(table.Remove("quiet"), "t-1");
  EXPECT_FALSE(table.Known("quiet"));
  EXPECT_FALSE(table.Seen("quiet", t5));
  EXPECT_FALSE(table.Remove("quiet"));
}

TEST(WorkerTableTest, ASecondReadyFromAKnownWorkerChangesNothingButWhenItWasHeard) {
  WorkerTable table;
  const Clock::time_point t0 = Clock::now();
  EXPECT_TRUE(table.Ready("a", ReadyWith(1), t0));
  table.Assign("t-1", t0 + std::chrono::seconds(10));
  const std::string id = table.List(t0, 0).front().worker_id();
  // The task on its way to it stays its own, and it is not idle twice over.
  EXPECT_FALSE(table.Ready("a", ReadyWith(1), t0 + std::chrono::seconds(5)));
  EXPECT_EQ(table.TaskOf("a"), "t-1");
  EXPECT_FALSE(table.Assign("t-2", t0));
  EXPECT_EQ(table.List(t0, 0).front().worker_id(), id);
  EXPECT_TRUE(table.Lost(t0 + std::chrono::seconds(6), t0 + std::chrono::seconds(4)).empty());
  table.Done("a");
  EXPECT_FALSE(table.Ready("a", ReadyWith(1), t0));
  EXPECT_EQ(table.Assign("t-2", t0), "a");
  EXPECT_FALSE(table.Assign("t-3", t0));
}

}  // namespace
}  // namespace evoslam
