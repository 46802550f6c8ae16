// Wall and CPU time of a measured run, for the bench and the window's error
// plot: with the measuring itself taken out, so that a figure is what the
// method would have cost without anyone looking.
#pragma once

#include <chrono>

namespace bounce {

// CPU time of this process, all threads, user and system, in seconds.
double cpu_seconds();

// Wall and CPU time of a run with the measuring taken out, so that a point's
// time is what the method would have cost without the bench looking at it.
class run_clock {
 public:
  double wall() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() - excluded_wall_;
  }
  double cpu() const { return cpu_seconds() - cpu_start_ - excluded_cpu_; }
  template <typename work>
  void exclude(work&& w) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_seconds();
    w();
    excluded_wall_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    excluded_cpu_ += cpu_seconds() - c0;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double cpu_start_ = cpu_seconds();
  double excluded_wall_ = 0.0, excluded_cpu_ = 0.0;
};

}  // namespace bounce
