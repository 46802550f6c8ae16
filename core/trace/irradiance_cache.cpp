#include "trace/irradiance_cache.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "base/directions.h"
#include "base/random_stream.h"

namespace bounce {
namespace {

using std::numbers::pi;

// A jitter in [0, 1) from a seed and a cell.
double jitter(std::uint64_t seed, std::uint64_t k) {
  return unit_interval(mix64(seed + golden_gamma * k));
}

// Ward & Heckbert's translation gradient, in the form Krivanek & Gautron
// give for cosine-weighted cells. Moving the point shifts the walls
// between neighbouring cells: the wall between theta rings j - 1 and j
// (at sin^2 theta = j / M) moves along u_k, the cell's mid-direction in
// the tangent plane; the wall between phi sectors k - 1 and k moves
// along v_k-, that wall's normal. Each wall moves by the distance moved
// over the nearer hit's distance, and passes light L_new - L_old. Misses
// are infinitely far: their walls do not move.
std::array<vec3, 3> translation_gradient(const std::vector<gather_sample>& cells, int m, int n, const vec3& t,
                                         const vec3& b) {
  std::array<vec3, 3> out{vec3(0.0), vec3(0.0), vec3(0.0)};
  auto at = [&](int j, int k) -> const gather_sample& {
    return cells[std::size_t(k) * std::size_t(m) + std::size_t(j)];
  };
  auto add = [&](const vec3& direction, double weight, const rgb& difference) {
    for (int ch = 0; ch < 3; ++ch) out[std::size_t(ch)] += direction * (weight * difference[ch]);
  };
  for (int k = 0; k < n; ++k) {
    const double mid = 2.0 * pi * (k + 0.5) / n, wall = 2.0 * pi * k / n;
    const vec3 u = std::cos(mid) * t + std::sin(mid) * b;
    const vec3 v = -std::sin(wall) * t + std::cos(wall) * b;  // the sector wall's normal, towards sector k
    for (int j = 0; j < m; ++j) {
      const gather_sample& here = at(j, k);
      if (j > 0) {
        const gather_sample& inner = at(j - 1, k);
        const double r = std::min(here.distance, inner.distance);
        const double sin2 = double(j) / m;  // the ring wall's sin^2 theta
        if (r > 0.0 && std::isfinite(r))
          add(u, 2.0 * pi / n * (1.0 - sin2) * std::sqrt(sin2) / r, here.radiance - inner.radiance);
      }
      const gather_sample& previous = at(j, (k + n - 1) % n);
      const double r = std::min(here.distance, previous.distance);
      if (n > 1 && r > 0.0 && std::isfinite(r)) {
        const double cos_in = std::sqrt(1.0 - double(j) / m), cos_out = std::sqrt(1.0 - double(j + 1) / m);
        const double sin_mid = std::sqrt((j + 0.5) / m), cos_mid = std::sqrt(1.0 - (j + 0.5) / m);
        add(v, cos_mid * (cos_in - cos_out) / (sin_mid * r), here.radiance - previous.radiance);
      }
    }
  }
  return out;
}

}  // namespace

int gather_irradiance(const vec3& position, const vec3& normal, int rays, std::uint64_t seed,
                      const std::function<gather_sample(const vec3& dir, std::uint64_t ray_seed)>& cast,
                      irradiance_record& out) {
  const int m = std::max(1, int(std::lround(std::sqrt(std::max(1, rays) / pi)))),
            n = std::max(1, int(std::lround(double(std::max(1, rays)) / m)));
  vec3 t, b;
  orthonormal_basis(normal, t, b);
  rgb sum(0.0);
  double inverse_distances = 0.0;
  std::array<vec3, 3> rotation{vec3(0.0), vec3(0.0), vec3(0.0)};
  std::vector<gather_sample> cells(std::size_t(m) * std::size_t(n));  // [k * m + j]
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j) {
      const std::uint64_t cell = std::uint64_t(k) * std::uint64_t(m) + std::uint64_t(j);
      const double u1 = (j + jitter(seed, 2 * cell)) / m, phi = 2.0 * pi * (k + jitter(seed, 2 * cell + 1)) / n;
      const double sin_theta = std::sqrt(u1), cos_theta = std::sqrt(std::max(0.0, 1.0 - u1));
      const vec3 dir =
          glm::normalize(sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * b + cos_theta * normal);
      const gather_sample g = cast(dir, seed ^ (0xD1B54A32D192ED03ull * (cell + 1)));
      cells[cell] = g;
      sum += g.radiance;
      if (g.distance > 0.0 && std::isfinite(g.distance)) inverse_distances += 1.0 / g.distance;
      // Turning the normal by d about u moves E by d u . (n x omega) L / cos
      // (per cosine-weighted sample), and n x omega = sin(theta) v with v
      // the base-plane direction a quarter turn on from phi (Ward &
      // Heckbert 1992, whose v points the other way).
      const vec3 v = -std::sin(phi) * t + std::cos(phi) * b;
      const double tan_theta = sin_theta / std::max(cos_theta, 1e-3);
      for (int ch = 0; ch < 3; ++ch) rotation[std::size_t(ch)] += v * (tan_theta * g.radiance[ch]);
    }
  const double scale = pi / double(m * n);
  out.position = position;
  out.normal = normal;
  out.irradiance = sum * scale;
  out.radius = inverse_distances > 0.0 ? double(m * n) / inverse_distances : std::numeric_limits<double>::infinity();
  for (int ch = 0; ch < 3; ++ch) out.rotation[std::size_t(ch)] = rotation[std::size_t(ch)] * scale;
  out.translation = translation_gradient(cells, m, n, t, b);
  return m * n;
}

double ward_weight(const irradiance_record& r, const vec3& p, const vec3& n) {
  const vec3 d = p - r.position;
  // The record in front of the point: the point lies behind the tangent
  // plane (averaged with its own) by more than a sliver of R.
  if (glm::dot(d, r.normal + n) * 0.5 < -0.05 * r.radius) return 0.0;
  const double e = glm::length(d) / r.radius + std::sqrt(std::max(0.0, 1.0 - glm::dot(n, r.normal)));
  return e > 0.0 ? 1.0 / e : std::numeric_limits<double>::infinity();
}

irradiance_cache::irradiance_cache(double accuracy, double cell) : accuracy_(accuracy), cell_(cell) {}

std::uint64_t irradiance_cache::key(long x, long y, long z) {
  constexpr std::uint64_t mask = (1ull << 21) - 1;
  return (std::uint64_t(x) & mask) << 42 | (std::uint64_t(y) & mask) << 21 | (std::uint64_t(z) & mask);
}

void irradiance_cache::add(const irradiance_record& r) {
  const auto index = std::uint32_t(records_.size());
  records_.push_back(r);
  // Into every cell the record may serve at the largest reach: weight over
  // 1 / (a reach) needs |p - p_i| < a reach R_i.
  const double reach = accuracy_ * max_reach * r.radius;
  std::size_t level = 0;
  double cell = cell_;
  while (cell < 2.0 * reach && level < 40) {
    cell *= 2.0;
    ++level;
  }
  if (levels_.size() <= level) levels_.resize(level + 1);
  const vec3 lo = (r.position - vec3(reach)) / cell, hi = (r.position + vec3(reach)) / cell;
  for (long x = long(std::floor(lo.x)); x <= long(std::floor(hi.x)); ++x)
    for (long y = long(std::floor(lo.y)); y <= long(std::floor(hi.y)); ++y)
      for (long z = long(std::floor(lo.z)); z <= long(std::floor(hi.z)); ++z)
        levels_[level][key(x, y, z)].push_back(index);
}

std::optional<rgb> irradiance_cache::lookup(const vec3& p, const vec3& n, double reach) const {
  const double threshold = 1.0 / (accuracy_ * reach);
  rgb sum(0.0);
  double weights = 0.0;
  double cell = cell_;
  for (const grid& level : levels_) {
    const auto it =
        level.find(key(long(std::floor(p.x / cell)), long(std::floor(p.y / cell)), long(std::floor(p.z / cell))));
    cell *= 2.0;
    if (it == level.end()) continue;
    for (const std::uint32_t i : it->second) {
      const irradiance_record& r = records_[i];
      const double w = ward_weight(r, p, n);
      if (!(w > threshold)) continue;
      if (!std::isfinite(w)) return r.irradiance;  // on the record itself
      const vec3 turn = glm::cross(r.normal, n), move = p - r.position;
      rgb e = r.irradiance;
      for (int ch = 0; ch < 3; ++ch)
        e[ch] += glm::dot(turn, r.rotation[std::size_t(ch)]) + glm::dot(move, r.translation[std::size_t(ch)]);
      sum += w * glm::max(e, rgb(0.0));
      weights += w;
    }
  }
  if (weights <= 0.0) return std::nullopt;
  return sum / weights;
}

}  // namespace bounce
