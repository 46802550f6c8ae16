#include "scene/texture.h"

#include <cmath>

namespace bounce {

namespace {

// Bilinear filtering with repeat: `channel(k)` of the texel k (row-major,
// row 0 the top), weighted around (u, v); texel centres at (i + 0.5) / size.
template <typename value, typename lookup>
value bilinear(const texture& t, const vec2& uv, lookup&& channel) {
  const double x = (uv.x - std::floor(uv.x)) * t.width - 0.5;
  const double y = (1.0 - (uv.y - std::floor(uv.y))) * t.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double wx = x - fx, wy = y - fy;
  auto texel = [&](double i, double j) {
    const int col = int(((long long)i % t.width + t.width) % t.width);
    const int row = int(((long long)j % t.height + t.height) % t.height);
    return channel(std::size_t(row) * t.width + col);
  };
  return (1 - wy) * ((1 - wx) * texel(fx, fy) + wx * texel(fx + 1, fy)) +
         wy * ((1 - wx) * texel(fx, fy + 1) + wx * texel(fx + 1, fy + 1));
}

}  // namespace

rgb texture_value(const texture& t, const vec2& uv) {
  if (t.kind == texture_kind::checker) {
    const double squares = std::floor(uv.x * t.scale) + std::floor(uv.y * t.scale);
    return std::fmod(std::abs(squares), 2.0) < 0.5 ? t.color0 : t.color1;
  }
  if (t.width <= 0 || t.height <= 0) return rgb(1.0);
  return bilinear<rgb>(t, uv,
                       [&](std::size_t k) { return rgb(t.texels[3 * k], t.texels[3 * k + 1], t.texels[3 * k + 2]); });
}

double texture_alpha(const texture& t, const vec2& uv) {
  if (t.kind != texture_kind::image || t.width <= 0 || t.height <= 0 ||
      t.alpha.size() != std::size_t(t.width) * std::size_t(t.height))
    return 1.0;
  return bilinear<double>(t, uv, [&](std::size_t k) { return double(t.alpha[k]); });
}

bool cut_out(const material& m, const std::vector<texture>& textures, const vec2& uv) {
  if (!(m.alpha_cutoff > 0.0)) return false;
  const double coverage = m.texture >= 0 && std::size_t(m.texture) < textures.size()
                              ? texture_alpha(textures[std::size_t(m.texture)], uv)
                              : 1.0;
  return coverage * m.alpha < m.alpha_cutoff;
}

rgb texture_mean(const texture& t) {
  if (t.kind == texture_kind::checker) return 0.5 * (t.color0 + t.color1);
  rgb sum(0.0);
  for (std::size_t i = 0; i + 2 < t.texels.size(); i += 3) sum += rgb(t.texels[i], t.texels[i + 1], t.texels[i + 2]);
  const std::size_t n = t.texels.size() / 3;
  return n ? sum / double(n) : rgb(1.0);
}

}  // namespace bounce
