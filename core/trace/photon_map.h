// A photon map (Jensen 1996): photons stored where they landed on diffuse
// surfaces, in a kd-tree (nanoflann) built once, and the density estimate
// that turns the photons near a point into irradiance. GL-free; the light
// pass that fills it is photon_tracing.h. nanoflann stays inside
// photon_map.cpp.
#pragma once

#include <cstdint>

#include <memory>
#include <vector>

#include "scene/scene.h"

namespace bounce {

struct photon {
  vec3 position{0.0};
  // Unit vector from `position` back towards where the photon came from
  // (the incident direction as a BRDF takes it, not the travel direction).
  vec3 incoming{0.0};
  rgb power{0.0};    // watts: flux arriving at the surface, before its reflectance
  vec3 normal{0.0};  // unit shading normal of the side it landed on
  int surface = -1;  // the side it landed on (the back of a two-sided surface has its own index)
};

// Memory of a photon map of `count` photons: the photons and the k-d
// tree's index over them (a figure checked before tracing them).
inline double photon_map_bytes(double count) {
  return count * double(sizeof(photon) + 2 * sizeof(std::uint32_t));
}

// How photons count by their distance d from the query point within the
// radius r.
//  box:  all alike: E = sum(power) / (pi r^2).
//  cone: weight 1 - d / (k r), normalised by 1 - 2 / (3 k) so that a uniform
//        density is estimated without bias (Jensen 1996, k = 1.1): photons at
//        the edge of the disc count less, which keeps caustic edges sharper.
enum class photon_filter { box, cone };
constexpr double cone_filter_k = 1.1;

// Photons whose stored normal is further than this (as a cosine) from the
// query normal belong to another surface: the other side of a thin wall,
// or a wall meeting the floor in a corner, and do not count.
constexpr double photon_normal_agreement = 0.5;

// Photons count only within this slope of the query's tangent plane
// (|offset . n| at most this times the distance): the search is a disc,
// not a sphere (Jensen's compressed sphere), so a parallel surface
// nearby, such as a floor under a table top, lends none of its light. On
// a curved surface of radius rho, photons count up to about rho / 2 away.
constexpr double photon_plane_slope = 0.25;

struct photon_estimate {
  rgb irradiance{0.0};  // W / m^2 (scene units squared)
  int photons = 0;      // how many counted
  double radius = 0.0;  // the radius used: the query's, or the k-th photon's distance when k were found
};

class photon_map {
 public:
  photon_map();
  explicit photon_map(std::vector<photon> photons);  // builds the kd-tree
  ~photon_map();
  photon_map(photon_map&&) noexcept;
  photon_map& operator=(photon_map&&) noexcept;

  const std::vector<photon>& photons() const;
  std::size_t size() const { return photons().size(); }
  bool empty() const { return photons().empty(); }
  rgb total_power() const;

  // Irradiance at `point` on a surface facing `normal` (unit) from the
  // nearest `max_photons` photons within `radius` that lie on a surface
  // facing the same way (photon_normal_agreement) and arrived from the
  // side `normal` faces. When `max_photons` such photons are found, the
  // radius shrinks to the distance of the farthest of them (the k-nearest
  // estimate); otherwise it stays `radius`. radius > 0, max_photons > 0.
  photon_estimate estimate(const vec3& point, const vec3& normal, double radius, int max_photons,
                           photon_filter filter = photon_filter::cone) const;
  rgb irradiance_estimate(const vec3& point, const vec3& normal, double radius, int max_photons,
                          photon_filter filter = photon_filter::cone) const {
    return estimate(point, normal, radius, max_photons, filter).irradiance;
  }

 private:
  struct tree;
  std::unique_ptr<tree> tree_;  // stable address: nanoflann's index keeps a reference to the points
};

}  // namespace bounce
