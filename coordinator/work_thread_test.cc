#include "coordinator/work_thread.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

namespace evoslam {
namespace {

TEST(WorkThreadTest, DoesTheWorkInTheOrderHandedOnAThreadOfItsOwn) {
  std::vector<int> done;
  std::promise<std::thread::id> ran_on;
  std::promise<void> finished;
  {
    WorkThread<int> thread([&](int& n, const std::stop_token&) {
      if (done.empty()) ran_on.set_value(std::this_thread::get_id());
      done.push_back(n);
      if (n == 99) finished.set_value();
    });
    for (int n = 0; n < 100; ++n) thread.Post(n);
    ASSERT_EQ(finished.get_future().wait_for(std::chrono::seconds(20)), std::future_status::ready);
  }
  EXPECT_NE(ran_on.get_future().get(), std::this_thread::get_id());
  ASSERT_EQ(done.size(), 100u);
  for (int n = 0; n < 100; ++n) EXPECT_EQ(done[n], n);
}

// Going, it finishes the piece under way, which sees the stop, and drops the rest undone.
TEST(WorkThreadTest, GoingItFinishesThePieceUnderWayAndDropsTheRest) {
  std::atomic<int> started{0};
  std::atomic<bool> saw_stop{false};
  {
    WorkThread<int> thread([&](int&, const std::stop_token& stop) {
      ++started;
      while (!stop.stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      saw_stop = true;
    });
    thread.Post(1);
    thread.Post(2);
    while (started == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(started, 1);
  EXPECT_TRUE(saw_stop);
}

}  // namespace
}  // namespace evoslam
