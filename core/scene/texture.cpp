#include "scene/texture.h"

#include <cmath>

namespace bounce {

rgb texture_value(const texture& t, const vec2& uv) {
  if (t.kind == texture_kind::checker) {
    const double squares = std::floor(uv.x * t.scale) + std::floor(uv.y * t.scale);
    return std::fmod(std::abs(squares), 2.0) < 0.5 ? t.color0 : t.color1;
  }
  if (t.width <= 0 || t.height <= 0) return rgb(1.0);
  // Texel centres at (i + 0.5) / width; rows counted from the top.
  const double x = (uv.x - std::floor(uv.x)) * t.width - 0.5;
  const double y = (1.0 - (uv.y - std::floor(uv.y))) * t.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double wx = x - fx, wy = y - fy;
  auto texel = [&](double i, double j) {
    const int col = int(((long long)i % t.width + t.width) % t.width);
    const int row = int(((long long)j % t.height + t.height) % t.height);
    const std::size_t k = (std::size_t(row) * t.width + col) * 3;
    return rgb(t.texels[k], t.texels[k + 1], t.texels[k + 2]);
  };
  return (1 - wy) * ((1 - wx) * texel(fx, fy) + wx * texel(fx + 1, fy)) +
         wy * ((1 - wx) * texel(fx, fy + 1) + wx * texel(fx + 1, fy + 1));
}

rgb texture_mean(const texture& t) {
  if (t.kind == texture_kind::checker) return 0.5 * (t.color0 + t.color1);
  rgb sum(0.0);
  for (std::size_t i = 0; i + 2 < t.texels.size(); i += 3) sum += rgb(t.texels[i], t.texels[i + 1], t.texels[i + 2]);
  const std::size_t n = t.texels.size() / 3;
  return n ? sum / double(n) : rgb(1.0);
}

}  // namespace bounce
