#include "measure/curves.h"

#include <cmath>

namespace bounce {

std::vector<bool> pareto_front(std::span<const double> seconds, std::span<const double> errors) {
  std::vector<bool> front(seconds.size(), false);
  for (std::size_t i = 0; i < seconds.size(); ++i) {
    if (std::isnan(errors[i]) || std::isnan(seconds[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < seconds.size() && !dominated; ++j) {
      if (j == i || std::isnan(errors[j]) || std::isnan(seconds[j])) continue;
      dominated =
          seconds[j] <= seconds[i] && errors[j] <= errors[i] && (seconds[j] < seconds[i] || errors[j] < errors[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

double growth_exponent(std::span<const double> x, std::span<const double> y) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    n += 1;
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  return n >= 2 && d > 0.0 ? (n * sxy - sx * sy) / d : not_measured;
}

double time_to_error(const bench_curve& curve, double target) {
  const bench_point* previous = nullptr;
  for (const bench_point& p : curve.points) {
    if (std::isnan(p.error)) continue;
    if (p.error <= target) {
      if (!previous || previous->error <= 0.0 || p.error <= 0.0 || target <= 0.0) return p.seconds;
      const double u = (std::log(target) - std::log(previous->error)) / (std::log(p.error) - std::log(previous->error));
      return std::exp(std::log(previous->seconds) + u * (std::log(p.seconds) - std::log(previous->seconds)));
    }
    previous = &p;
  }
  return not_measured;
}

}  // namespace bounce
