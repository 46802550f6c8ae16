// Error-against-time curves and the maths on them: where a run stands on
// the Pareto front of speed against error, how its cost grows, when it
// first reaches an error.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "measure/surface_means.h"

namespace bounce {

inline constexpr double not_measured = std::numeric_limits<double>::quiet_NaN();

struct bench_point {
  double seconds = 0.0;      // wall time from the loaded scene to this solution (measuring excluded)
  double cpu_seconds = 0.0;  // CPU time of all threads over the same span
  std::uint64_t steps = 0;
  std::uint64_t rays = 0;
  double remaining = not_measured;
  double error = not_measured;           // relative RMSE: per vertex (closed form) or over the picture
  double max_error = not_measured;       // largest relative error, same samples
  double power_error = not_measured;     // reflected power against the closed form, relative
  double balance_error = not_measured;   // progressive: |emitted + received - shot - unshot| / (emitted + received)
  double residual = not_measured;        // matrix solvers: max |(I - R K) B - b| / max |b|
  std::size_t elements = 0;              // elements of the mesh at this point (adaptive meshing grows it)
  std::vector<surface_mean> surfaces{};  // pictures: the mean per material against the reference's
};

// One curve of the plot: a method/setting and its error over time.
struct bench_curve {
  std::string method;  // raycast, hemicube, reference-lu, gauss-seidel, path, and "+ two-pass" variants
  std::vector<bench_point> points;
};

// A point (seconds, error) is on the Pareto front when no other point is
// at least as fast and at least as accurate, and strictly better in one.
// Returns one flag per point; points whose error was not measured are never
// on it.
std::vector<bool> pareto_front(std::span<const double> seconds, std::span<const double> errors);

// Least-squares slope of log(y) against log(x): the exponent of y ~ x^k.
double growth_exponent(std::span<const double> x, std::span<const double> y);

// The earliest time at which a curve's error is at or below `target`
// (linearly interpolated in log-log between stops; NaN if never).
double time_to_error(const bench_curve& curve, double target);

}  // namespace bounce
