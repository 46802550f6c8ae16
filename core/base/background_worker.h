// Work in the background: tasks run one at a time, in the order posted, on
// one thread that lives as long as the object. The window's still, the
// error plot's reference and measurements, and the trace command all use
// it, so none of them keeps a thread of its own. Cancelling is a task's own
// business (a flag it polls, such as trace_progress::cancel).
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace bounce {

class background_worker {
 public:
  background_worker();
  // Drops the tasks not started and waits for the running one.
  ~background_worker();
  background_worker(const background_worker&) = delete;
  background_worker& operator=(const background_worker&) = delete;

  void post(std::function<void()> task);
  // A task running or waiting.
  bool busy() const;
  // Blocks until no task is running or waiting.
  void wait_idle() const;

 private:
  void run();

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<std::function<void()>> tasks_;
  bool running_task_ = false;
  bool quit_ = false;
  std::thread thread_;  // last: it starts in the constructor and uses every member above
};

}  // namespace bounce
