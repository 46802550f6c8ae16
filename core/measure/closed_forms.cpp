#include "measure/closed_forms.h"

#include <cmath>
#include <numbers>

namespace bounce {

using std::numbers::pi;

double corner_point_rectangle(double a, double b, double c) {
  const double x = a / c, y = b / c;
  return 1.0 / (2.0 * pi) *
         (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)));
}

double point_parallel_rectangle(double x0, double x1, double y0, double y1, double c) {
  // The corner term is odd in each side: signed sides add and subtract.
  return corner_point_rectangle(x1, y1, c) - corner_point_rectangle(x0, y1, c) - corner_point_rectangle(x1, y0, c) +
         corner_point_rectangle(x0, y0, c);
}

double mirrored_point_parallel_rectangle(double x0, double x1, double y0, double y1, double emitter_height,
                                         double mirror_height, double kr) {
  return kr * point_parallel_rectangle(x0, x1, y0, y1, 2.0 * mirror_height - emitter_height);
}

double parallel_rectangles(double a, double b, double c) {
  const double x = a / c, y = b / c;
  return 2.0 / (pi * x * y) *
         (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
          x * std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)) +
          y * std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) - x * std::atan(x) - y * std::atan(y));
}

double perpendicular_rectangles(double l, double w, double h) {
  const double W = w / l, H = h / l, s = H * H + W * W;
  const double log_term = std::log((1 + W * W) * (1 + H * H) / (1 + s)) +
                          W * W * std::log(W * W * (1 + s) / ((1 + W * W) * s)) +
                          H * H * std::log(H * H * (1 + s) / ((1 + H * H) * s));
  return 1.0 / (pi * W) *
         (W * std::atan(1 / W) + H * std::atan(1 / H) - std::sqrt(s) * std::atan(1 / std::sqrt(s)) + 0.25 * log_term);
}

double coaxial_discs(double r1, double r2, double h) {
  const double R1 = r1 / h, R2 = r2 / h, X = 1 + (1 + R2 * R2) / (R1 * R1);
  return 0.5 * (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1)));
}

}  // namespace bounce
