#include "image/tonemap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bounce {

double linear_to_srgb(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
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
