// What the command line prints besides errors: one switch for --quiet, and
// a progress line that redraws itself on a terminal (stderr) and stays
// silent in pipes, logs and with --quiet, as pbrt and Mitsuba do.
#pragma once

#include <chrono>
#include <cstdarg>
#include <string>
#include <string_view>

#include "radiosity/solver_settings.h"

namespace bounce {

// --quiet: no progress and no reports, only warnings and errors.
void set_quiet(bool quiet);
bool quiet();

// printf to stdout unless quiet.
void say(const char* format, ...) __attribute__((format(printf, 1, 2)));

// "solving [#####.....] 48%  residual 0.3%  2.1 s", redrawn in place at most
// ten times a second; erased by done() (or the destructor) so that the
// report that follows starts on a clean line.
class progress_line {
 public:
  explicit progress_line(std::string what);
  ~progress_line();
  progress_line(const progress_line&) = delete;
  progress_line& operator=(const progress_line&) = delete;

  // fraction in [0, 1]; detail is shown after the percentage.
  void update(double fraction, const std::string& detail = {});
  void done();

  bool shown() const { return enabled_; }

 private:
  std::string what_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

// How far a solve is from its stopping point, in [0, 1]: the remaining
// fraction on a log scale from 1 down to `until`, or the time limit when
// that is nearer.
double solve_progress(double remaining, double until, double seconds, double time_limit);

// What a solver's steps and remaining fraction are called where a user
// reads them: "shots" and "unshot" for the progressive solver, "steps"
// and "residual" for the hierarchical one (solution.h says what each is).
std::string_view steps_word(solver_method method);
std::string_view remaining_word(solver_method method);

// "residual 0.312%": the detail of a solve's progress line.
std::string remaining_text(solver_method method, double remaining);

}  // namespace bounce
