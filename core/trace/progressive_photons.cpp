#include "trace/progressive_photons.h"

#include <cmath>
#include <numbers>

namespace bounce {

double ppm_radius(double first, int pass, double alpha) {
  double r2 = first * first;
  for (int i = 1; i < pass; ++i) r2 *= (i + alpha) / (i + 1.0);
  return std::sqrt(r2);
}

caustic_hit_grid::caustic_hit_grid(const std::vector<caustic_hit>& hits, double cell) : hits_(hits), cell_(cell) {
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const vec3 c = hits[i].position / cell_;
    grid_[key(long(std::floor(c.x)), long(std::floor(c.y)), long(std::floor(c.z)))].push_back(std::uint32_t(i));
  }
}

std::uint64_t caustic_hit_grid::key(long x, long y, long z) const {
  constexpr std::uint64_t mask = (1ull << 21) - 1;
  return (std::uint64_t(x) & mask) << 42 | (std::uint64_t(y) & mask) << 21 | (std::uint64_t(z) & mask);
}

void caustic_hit_grid::add_pass(const std::vector<photon>& photons, double radius, std::vector<rgb>& irradiance) const {
  const double r2 = radius * radius, area = std::numbers::pi * r2;
  for (const photon& ph : photons) {
    const vec3 c = ph.position / cell_;
    const long cx = long(std::floor(c.x)), cy = long(std::floor(c.y)), cz = long(std::floor(c.z));
    for (long x = cx - 1; x <= cx + 1; ++x)
      for (long y = cy - 1; y <= cy + 1; ++y)
        for (long z = cz - 1; z <= cz + 1; ++z) {
          const auto it = grid_.find(key(x, y, z));
          if (it == grid_.end()) continue;
          for (const std::uint32_t h : it->second) {
            const caustic_hit& hit = hits_[h];
            const vec3 d = ph.position - hit.position;
            if (glm::dot(d, d) > r2 || glm::dot(ph.normal, hit.normal) <= photon_normal_agreement ||
                glm::dot(ph.incoming, hit.normal) <= 0.0)
              continue;
            irradiance[h] += ph.power / area;
          }
        }
  }
}

}  // namespace bounce
