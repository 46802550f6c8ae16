#include "image/tonemap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bounce {

double linear_to_srgb(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double filmic_curve(double x) {
  x = std::max(x, 0.0);
  return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

double display_to_linear(double encoded, bool filmic) {
  encoded = std::clamp(encoded, 0.0, 1.0);
  const double linear = encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
  if (!filmic) return linear;
  // filmic_curve(x) = y: (2.51 - 2.43 y) x^2 + (0.03 - 0.59 y) x - 0.14 y = 0,
  // whose positive root is x; the curve reaches 1 at its root for y = 1.
  const double y = std::min(linear, 1.0);
  const double a = 2.51 - 2.43 * y, b = 0.03 - 0.59 * y, c = -0.14 * y;
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

glm::u8vec3 to_srgb8(const rgb& radiance, double exposure) {
  glm::u8vec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<std::uint8_t>(std::lround(255.0 * linear_to_srgb(radiance[c] * exposure)));
  return out;
}

double auto_exposure(std::span<const rgb> radiance) {
  std::vector<double> l;
  l.reserve(radiance.size());
  for (const rgb& c : radiance) l.push_back(luminance(c));
  if (l.empty()) return 1.0;
  auto at = l.begin() + std::ptrdiff_t(0.95 * double(l.size() - 1));
  std::nth_element(l.begin(), at, l.end());
  return *at > 0.0 ? 0.8 / *at : 1.0;
}

}  // namespace bounce
