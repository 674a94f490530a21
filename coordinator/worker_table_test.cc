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
  EXPECT_EQ(table.Assign("t-1", t0, t0 + std::chrono::seconds(10)), "a");
  EXPECT_EQ(table.Assign("t-2", t0, t0 + std::chrono::seconds(10)), "b");
  EXPECT_FALSE(table.Assign("t-3", t0, t0));
  EXPECT_EQ(table.TaskOf("a"), "t-1");
  EXPECT_EQ(table.busy(), 2u);
  EXPECT_EQ(table.HeldFor("a", t0 + std::chrono::seconds(3)), std::chrono::seconds(3));
  table.Done("b");
  EXPECT_FALSE(table.HeldFor("b", t0 + std::chrono::seconds(3)));
  EXPECT_FALSE(table.HeldFor("nobody", t0));
  table.Done("a");
  EXPECT_EQ(table.busy(), 0u);
  EXPECT_EQ(table.Assign("t-3", t0, t0), "b");  // b has been idle longer
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
  table.Assign("t-1", t0, t0 + std::chrono::seconds(100));  // quiet
  table.Assign("t-2", t0, t0 + std::chrono::seconds(1));    // slow
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
  EXPECT_TRUE(table.Ready("a", ReadyWith(1), t0).is_new);
  table.Assign("t-1", t0, t0 + std::chrono::seconds(10));
  const std::string id = table.List(t0, 0).front().worker_id();
  // The task on its way to it stays its own, and it is not idle twice over.
  EXPECT_FALSE(table.Ready("a", ReadyWith(1), t0 + std::chrono::seconds(5)).is_new);
  EXPECT_EQ(table.TaskOf("a"), "t-1");
  EXPECT_FALSE(table.Assign("t-2", t0, t0));
  EXPECT_EQ(table.List(t0, 0).front().worker_id(), id);
  EXPECT_TRUE(table.Lost(t0 + std::chrono::seconds(6), t0 + std::chrono::seconds(4)).empty());
  table.Done("a");
  EXPECT_FALSE(table.Ready("a", ReadyWith(1), t0).is_new);
  EXPECT_EQ(table.Assign("t-2", t0, t0), "a");
  EXPECT_FALSE(table.Assign("t-3", t0, t0));
}

proto::Ready ReadyOf(const std::string& instance) {
  proto::Ready r = ReadyWith(1);
  r.set_instance(instance);
  return r;
}

// A worker that gave up on a stalled coordinator comes back on a new connection: its old entry,
// which no message reaches any more, must not stay a worker that takes tasks.
TEST(WorkerTableTest, ANewConnectionOfAKnownInstanceReplacesTheOldOne) {
  WorkerTable table;
  const Clock::time_point t0 = Clock::now();
  table.Ready("old", ReadyOf("i-1"), t0);
  table.Ready("other", ReadyOf("i-2"), t0);
  table.Assign("t-1", t0, t0 + std::chrono::seconds(10));  // old
  table.Done("old");
  table.Assign("t-2", t0, t0 + std::chrono::seconds(10));      // other
  table.Assign("t-3", t0, t0 + std::chrono::seconds(10));      // old
  const std::string id = table.List(t0, 0).at(0).worker_id();  // listed by identity: "old" first

  const WorkerTable::Arrival back = table.Ready("new", ReadyOf("i-1"), t0);
  EXPECT_TRUE(back.is_new);
  EXPECT_EQ(back.replaced, "old");
  EXPECT_EQ(back.replaced_task, "t-3");
  EXPECT_FALSE(table.Known("old"));
  EXPECT_EQ(table.size(), 2u);
  EXPECT_EQ(table.Assign("t-3", t0, t0), "new");
  for (const proto::WorkerInfo& w : table.List(t0, 0)) {
    if (w.worker_id() == id) {
      EXPECT_EQ(w.tasks_done(), 1u) << "its counts carry over";
    }
  }
  // Workers that send no instance are never taken for one another.
  table.Ready("x", ReadyWith(1), t0);
  EXPECT_FALSE(table.Ready("y", ReadyWith(1), t0).replaced);
}

TEST(WorkerTableTest, AQuarantinedWorkerGetsNoWorkUntilReleasedEvenAfterReconnecting) {
  WorkerTable table;
  const Clock::time_point t0 = Clock::now();
  table.Ready("a", ReadyOf("i-1"), t0);
  table.Ready("b", ReadyOf("i-2"), t0);
  ASSERT_EQ(table.Assign("t-1", t0, t0 + std::chrono::seconds(10)), "a");
  EXPECT_EQ(table.Failed("a"), 1);
  ASSERT_EQ(table.Assign("t-1", t0, t0 + std::chrono::seconds(10)), "b");
  table.Done("b");
  ASSERT_EQ(table.Assign("t-2", t0, t0 + std::chrono::seconds(10)), "a");
  EXPECT_EQ(table.Failed("a"), 2);
  ASSERT_EQ(table.Assign("t-2", t0, t0 + std::chrono::seconds(10)), "b");
  table.Done("b");
  ASSERT_EQ(table.Assign("t-3", t0, t0 + std::chrono::seconds(10)), "a");
  EXPECT_EQ(table.Quarantine("a", t0 + std::chrono::seconds(60), "its disk is full"), "t-3");

  EXPECT_EQ(table.Assign("t-3", t0, t0), "b");
  table.Done("b");
  EXPECT_EQ(table.Assign("t-4", t0, t0), "b");
  EXPECT_FALSE(table.Assign("t-5", t0, t0)) << "a quarantined worker was given work";
  EXPECT_EQ(table.quarantined(), 1u);
  const auto listed = table.List(t0, 1000.0);
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_DOUBLE_EQ(listed[0].quarantined_until_unix_s(), 1060.0);
  EXPECT_EQ(listed[0].quarantine_reason(), "its disk is full");
  EXPECT_EQ(listed[1].quarantined_until_unix_s(), 0.0);

  // Reconnecting, on a new connection or the same, does not end it.
  EXPECT_TRUE(table.Ready("a2", ReadyOf("i-1"), t0 + std::chrono::seconds(1)).quarantined);
  table.Remove("a2");
  EXPECT_TRUE(table.Ready("a", ReadyWith(1), t0 + std::chrono::seconds(1)).quarantined);
  EXPECT_TRUE(table.Release(t0 + std::chrono::seconds(59)).empty());
  EXPECT_FALSE(table.Assign("t-5", t0, t0));
  EXPECT_EQ(table.Release(t0 + std::chrono::seconds(60)), std::vector<std::string>{"a"});
  EXPECT_EQ(table.quarantined(), 0u);
  EXPECT_EQ(table.Assign("t-5", t0, t0), "a");
  // Its quarantine is over for good: a later connection is in the pool at once.
  EXPECT_FALSE(table.Ready("a3", ReadyOf("i-1"), t0 + std::chrono::seconds(61)).quarantined);
}

TEST(WorkerTableTest, ASucceededTaskEndsAWorkersRunOfFaults) {
  WorkerTable table;
  const Clock::time_point t0 = Clock::now();
  table.Ready("a", ReadyWith(1), t0);
  table.Assign("t-1", t0, t0);
  EXPECT_EQ(table.Failed("a"), 1);
  table.Assign("t-1", t0, t0);
  table.Done("a");
  table.Assign("t-2", t0, t0);
  EXPECT_EQ(table.Failed("a"), 1);
  EXPECT_EQ(table.Failed("a"), 0) << "a worker with no task in hand failed nothing";
}

}  // namespace
}  // namespace evoslam
