#include "base/background_worker.h"

#include <cstdio>
#include <exception>

namespace bounce {

background_worker::background_worker() : thread_([this] { run(); }) {}

background_worker::~background_worker() {
  std::deque<std::function<void()>> dropped;  // released outside the lock
  {
    const std::lock_guard lock(mutex_);
    quit_ = true;
    dropped.swap(tasks_);
  }
  changed_.notify_all();
  thread_.join();
}

void background_worker::post(std::function<void()> task) {
  {
    const std::lock_guard lock(mutex_);
    tasks_.push_back(std::move(task));
  }
  changed_.notify_all();
}

bool background_worker::busy() const {
  const std::lock_guard lock(mutex_);
  return running_task_ || !tasks_.empty();
}

void background_worker::wait_idle() const {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !running_task_ && tasks_.empty(); });
}

void background_worker::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return quit_ || !tasks_.empty(); });
    if (quit_) return;
    std::function<void()> task = std::move(tasks_.front());
    tasks_.pop_front();
    running_task_ = true;
    lock.unlock();
    try {
      task();
    } catch (const std::exception& e) {  // e.g. out of memory for a huge still: the program goes on
      std::fprintf(stderr, "error: background task failed: %s\n", e.what());
    }
    task = nullptr;  // what it holds is released outside the lock
    lock.lock();
    running_task_ = false;
    changed_.notify_all();
  }
}

}  // namespace bounce
