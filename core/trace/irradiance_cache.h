// An irradiance cache (Ward, Rubinstein & Clear 1988, with the rotation
// gradient of Ward & Heckbert 1992): indirect irradiance gathered at sparse
// points and interpolated between them, for the final gather of the
// two-pass still. GL-free; the tracer decides where records go
// (ray_tracer.cpp), this holds them and answers lookups.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include "scene/scene.h"

namespace bounce {

struct irradiance_record {
  vec3 position{0.0};
  vec3 normal{0.0};  // unit shading normal
  rgb irradiance{0.0};
  double radius = 0.0;  // R: harmonic mean distance to what the gather rays hit, clamped
  // dE per radian of rotation of the normal, per channel: E(n) ~ E + (n_record x n) . rotation[c].
  std::array<vec3, 3> rotation{vec3(0.0), vec3(0.0), vec3(0.0)};
  // dE per unit of distance moved in the tangent plane, per channel:
  // E(p) ~ E + (p - position) . translation[c].
  std::array<vec3, 3> translation{vec3(0.0), vec3(0.0), vec3(0.0)};
};

// What a gather ray in direction `dir` sees: the radiance arriving back
// along it, and the distance to its first hit (infinity if none).
struct gather_sample {
  rgb radiance{0.0};
  double distance = 0.0;
};

// The irradiance at `position` facing `normal` from `rays` cosine-weighted
// directions, stratified in M x N cells of (sin^2 theta, phi) with
// M = sqrt(rays / pi) and N = rays / M (Ward's proportions), each cell
// jittered by the seed: E = pi / (M N) sum L. Also the harmonic mean
// distance (unclamped), and the rotation and translation gradients (Ward &
// Heckbert 1992, the latter from how L changes between neighbouring cells
// and how far away their hits are). Returns the number of rays cast
// through `cast`.
int gather_irradiance(const vec3& position, const vec3& normal, int rays, std::uint64_t seed,
                      const std::function<gather_sample(const vec3& dir, std::uint64_t ray_seed)>& cast,
                      irradiance_record& out);

// Ward's weight of a record at (p, n): 1 / (|p - p_i| / R_i + sqrt(1 - n . n_i)),
// and zero when the record lies in front of the point (the point is behind
// the record's tangent plane, averaged with its own: the record may see
// light the point does not).
double ward_weight(const irradiance_record& r, const vec3& p, const vec3& n);

class irradiance_cache {
 public:
  // `accuracy` is Ward's a: a record serves points where its weight is
  // over 1 / a. `cell` is the finest lookup grid's cell size (any
  // positive value; about the smallest record's reach is best).
  irradiance_cache(double accuracy, double cell);

  void add(const irradiance_record& r);  // not thread-safe; lookups are
  std::size_t size() const { return records_.size(); }
  const std::vector<irradiance_record>& records() const { return records_; }
  double accuracy() const { return accuracy_; }

  // The weighted mean of the records whose weight at (p, n) exceeds
  // 1 / (a * reach), each extrapolated by its rotation gradient; nothing
  // when there are none. reach 1 is Ward's test; the still accepts up to
  // 2 before it gathers on the spot (sub-pixel samples between records).
  std::optional<rgb> lookup(const vec3& p, const vec3& n, double reach = 1.0) const;

  static constexpr double max_reach = 2.0;

 private:
  using grid = std::unordered_map<std::uint64_t, std::vector<std::uint32_t>>;  // cell -> records reaching into it
  static std::uint64_t key(long x, long y, long z);
  double accuracy_, cell_;
  std::vector<irradiance_record> records_;
  // Grids of cells cell_ * 2^k: a record goes into the finest whose cells are at least twice its reach, so it lands in
  // at most eight cells however large it is (Ward's octree, flattened).
  std::vector<grid> levels_;
};

}  // namespace bounce
