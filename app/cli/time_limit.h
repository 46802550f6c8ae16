// --time for the commands that solve (solve, render, trace, bake): the
// limit counts from the command's start, so loading and meshing are inside
// it, not only the solver's steps. Loading and meshing cannot stop halfway
// with something to show: a watchdog ends the command there (exit 1, with
// the reason, nothing written). The solver's steps then get the time left,
// and heed it within a step (run_solver).
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>

#include "radiosity/solver_settings.h"

namespace bounce {

// Seconds since the process started.
double seconds_since_start();

// `stop` with the time left: its seconds less those since the start (at
// least a nanosecond, so a limit that ran out stops after one step).
stop_criterion with_time_left(const stop_criterion& stop);

// While armed, ends the process with exit 1 when `seconds` since the
// start have passed, saying so on standard error. 0: no limit.
class setup_time_limit {
 public:
  explicit setup_time_limit(double seconds);
  ~setup_time_limit();
  setup_time_limit(const setup_time_limit&) = delete;
  setup_time_limit& operator=(const setup_time_limit&) = delete;

  void disarm();

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool disarmed_ = false;
  std::thread watchdog_;
};

// Disarms the command's setup_time_limit, if one is armed: the scene is
// loaded and meshed, and the solver takes the time left from here.
void setup_finished();

}  // namespace bounce
