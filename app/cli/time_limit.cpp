#include "cli/time_limit.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "common/exit_code.h"

namespace bounce {
namespace {

using clock_type = std::chrono::steady_clock;

// Read when the program is loaded, before main.
const clock_type::time_point program_start = clock_type::now();

std::atomic<setup_time_limit*> armed{nullptr};

}  // namespace

double seconds_since_start() {
  return std::chrono::duration<double>(clock_type::now() - program_start).count();
}

stop_criterion with_time_left(const stop_criterion& stop) {
  stop_criterion left = stop;
  if (stop.seconds > 0.0) left.seconds = std::max(1e-9, stop.seconds - seconds_since_start());
  return left;
}

setup_time_limit::setup_time_limit(double seconds) {
  if (!(seconds > 0.0)) return;
  armed.store(this);
  const auto deadline =
      program_start + std::chrono::duration_cast<clock_type::duration>(std::chrono::duration<double>(seconds));
  watchdog_ = std::thread([this, deadline, seconds] {
    std::unique_lock lock(mutex_);
    if (changed_.wait_until(lock, deadline, [this] { return disarmed_; })) return;
    std::fprintf(stderr,
                 "error: --time %g s ran out while loading and meshing the scene (%.1f s), before the solver's "
                 "first step; nothing written (give more time, or a coarser mesh with --max-edge)\n",
                 seconds, seconds_since_start());
    std::fflush(stderr);
    std::_Exit(exit_input_error);
  });
}

setup_time_limit::~setup_time_limit() {
  disarm();
  setup_time_limit* self = this;
  armed.compare_exchange_strong(self, nullptr);
}

void setup_time_limit::disarm() {
  if (!watchdog_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    disarmed_ = true;
  }
  changed_.notify_one();
  watchdog_.join();
}

void setup_finished() {
  if (setup_time_limit* limit = armed.exchange(nullptr)) limit->disarm();
}

}  // namespace bounce
