#include "cli/console.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <unistd.h>

namespace bounce {
namespace {

bool quiet_flag = false;

}  // namespace

void set_quiet(bool q) {
  quiet_flag = q;
}

bool quiet() {
  return quiet_flag;
}

void say(const char* format, ...) {
  if (quiet_flag) return;
  va_list args;
  va_start(args, format);
  std::vfprintf(stdout, format, args);
  va_end(args);
  std::fflush(stdout);
}

progress_line::progress_line(std::string what)
    : what_(std::move(what)),
      enabled_(!quiet_flag && ::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_(start_ - std::chrono::seconds(1)) {}

progress_line::~progress_line() {
  done();
}

void progress_line::update(double fraction, const std::string& detail) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  constexpr int width = 24;
  const int filled = int(fraction * width + 0.5);
  const double seconds = std::chrono::duration<double>(now - start_).count();
  std::string bar(std::size_t(filled), '#');
  bar.append(std::size_t(width - filled), '.');
  // \r and clear-to-end-of-line: the line shrinks cleanly when the detail does.
  std::fprintf(stderr, "\r%s [%s] %3d%%  %s  %.1f s\x1b[K", what_.c_str(), bar.c_str(), int(fraction * 100.0),
               detail.c_str(), seconds);
  std::fflush(stderr);
  drawn_ = true;
}

void progress_line::done() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\x1b[K");
  std::fflush(stderr);
  drawn_ = false;
}

double solve_progress(double remaining, double until, double seconds, double time_limit) {
  double p = 0.0;
  if (until > 0.0 && until < 1.0 && remaining > 0.0)
    p = std::log(std::min(1.0, remaining)) / std::log(until);
  else if (remaining <= until)
    p = 1.0;
  if (time_limit > 0.0) p = std::max(p, seconds / time_limit);
  return std::clamp(std::isfinite(p) ? p : 0.0, 0.0, 1.0);
}

std::string_view steps_word(solver_method method) {
  return method == solver_method::progressive ? "shots" : "steps";
}

std::string_view remaining_word(solver_method method) {
  return method == solver_method::progressive ? "unshot" : "residual";
}

std::string remaining_text(solver_method method, double remaining) {
  char text[48];
  std::snprintf(text, sizeof text, "%s %.3g%%", std::string(remaining_word(method)).c_str(), 100.0 * remaining);
  return text;
}

}  // namespace bounce
