// The one helper for background work: tasks in the order posted, one at a
// time; idle once all have run; tasks not started are dropped on exit.
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "base/background_worker.h"

namespace bounce {
namespace {

TEST(BackgroundWorker, RunsTasksOneAtATimeInOrder) {
  std::vector<int> order;  // written by the tasks only: one at a time, no lock needed
  std::atomic<int> running{0}, most{0};
  {
    background_worker jobs;
    for (int i = 0; i < 20; ++i)
      jobs.post([&, i] {
        most = std::max(most.load(), ++running);
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        order.push_back(i);
        --running;
      });
    jobs.wait_idle();
    EXPECT_FALSE(jobs.busy());
  }
  ASSERT_EQ(order.size(), 20u);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(order[std::size_t(i)], i);
  EXPECT_EQ(most.load(), 1);
}

TEST(BackgroundWorker, AFailingTaskDoesNotStopTheOthers) {
  std::atomic<int> ran{0};
  background_worker jobs;
  jobs.post([] { throw std::runtime_error("out of memory, say"); });
  jobs.post([&] { ++ran; });
  jobs.wait_idle();
  EXPECT_EQ(ran.load(), 1);
}

TEST(BackgroundWorker, DestructionDropsTasksNotStarted) {
  std::atomic<int> ran{0};
  std::atomic<bool> started{false}, release{false};
  {
    background_worker jobs;
    jobs.post([&] {
      started = true;
      while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      ++ran;
    });
    for (int i = 0; i < 5; ++i) jobs.post([&] { ++ran; });
    while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_TRUE(jobs.busy());
    std::thread releaser([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      release = true;
    });
    releaser.detach();
  }  // waits for the running task, drops the five waiting
  EXPECT_EQ(ran.load(), 1);
}

}  // namespace
}  // namespace bounce
