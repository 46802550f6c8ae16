// Progressive photon mapping's bookkeeping (the probabilistic form of
// Knaus & Zwicker 2011): the still's caustic shading points are found once,
// each photon pass adds its photons within a global radius that shrinks
// from pass to pass, and the passes' estimates are averaged, which
// converges to the caustic irradiance (no k-nearest bias left). GL-free.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "trace/photon_map.h"

namespace bounce {

// A diffuse point where the still wants the caustic irradiance, and what
// it is worth to its pixel: the pixel gains weight x irradiance.
struct caustic_hit {
  vec3 position{0.0};
  vec3 normal{0.0};  // unit shading normal, facing the way the eye ray came from
  rgb weight{0.0};   // throughput x rho / pi / samples of the pixel
  int pixel = -1;
};

// The radius of pass `pass` (1-based) from the first pass's: r_{i+1}^2 =
// r_i^2 (i + alpha) / (i + 1), alpha in (0, 1).
double ppm_radius(double first, int pass, double alpha);

// The hits in a uniform grid whose cells are at least as large as any
// radius used later, so that a photon meets every hit within the radius in
// the 27 cells around it.
class caustic_hit_grid {
 public:
  caustic_hit_grid(const std::vector<caustic_hit>& hits, double cell);

  // Adds to irradiance[h] (one entry per hit) the box-filtered estimate of
  // this pass: the power of the photons within `radius` of hit h, over
  // pi radius^2. Photons count by photon_map::estimate's rules: on a
  // surface facing the same way, arriving from the side the hit faces.
  void add_pass(const std::vector<photon>& photons, double radius, std::vector<rgb>& irradiance) const;

 private:
  std::uint64_t key(long x, long y, long z) const;
  const std::vector<caustic_hit>& hits_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_;
};

}  // namespace bounce
