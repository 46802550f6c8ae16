// Ray queries against the scene for the ray tracers: Embree 3 over the
// triangles of polygons and tessellated patches, plus user geometry that
// intersects spheres and quadrics exactly (in double precision). Embree's
// types stay inside ray_scene.cpp.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <span>

#include "scene/scene.h"

namespace bounce {

struct ray_hit {
  double t = 0.0;
  vec3 point{0.0};
  vec3 normal{0.0};  // unit shading normal; the surface's own side (polygon winding, sphere outward, quadric gradient)
  vec3 face_normal{0.0};  // unit geometric normal on the same side (the triangle's, for tessellated surfaces)
  vec2 uv{0.0};
  int surface = -1;
  int material = -1;
};

// A ray in floats, as Embree stores it (ray_scene::embree_closest_hits).
struct float_ray {
  float origin[3];
  float direction[3];
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
};

// A point on the emitting surfaces, drawn uniformly by area.
struct emitter_sample {
  vec3 point{0.0};
  vec3 normal{0.0};     // the emitting side
  rgb radiance{0.0};    // ke, emitted on the normal's side only
  double pdf_area = 0;  // 1 / total emitting area
};

class ray_scene {
 public:
  // Patches (Bezier, B-spline) are traced through their tessellation at
  // `patch_edge` with interpolated normals (0: a quarter of the default
  // element size, finer than the radiosity mesh so silhouettes stay
  // smooth); spheres and quadrics exactly.
  explicit ray_scene(const scene& s, double patch_edge = 0.0);
  ~ray_scene();
  ray_scene(const ray_scene&) = delete;
  ray_scene& operator=(const ray_scene&) = delete;

  // Closest hit with t in (t_min, t_max) along origin + t * direction.
  // Rays leaving a surface must start lifted off it along its normal (see
  // ray_scene.cpp): a bare epsilon on t is not enough for grazing rays.
  std::optional<ray_hit> intersect(const vec3& origin, const vec3& direction, double t_min = 0.0,
                                   double t_max = std::numeric_limits<double>::infinity()) const;

  // The closest hits of many rays over one t range, traced in Embree's
  // 8-wide packets (rtcIntersect8): for coherent rays, such as a tile's
  // primary rays or one pixel's samples, faster than one intersect() each
  // (docs/performance.md, "Ray core"). hits[i] is what intersect(origins[i],
  // directions[i], t_min, t_max) returns, up to float round-off in
  // Embree's barycentrics. The three spans must be of one size
  // (std::invalid_argument otherwise).
  void intersect_packets(std::span<const vec3> origins, std::span<const vec3> directions,
                         std::span<std::optional<ray_hit>> hits, double t_min = 0.0,
                         double t_max = std::numeric_limits<double>::infinity()) const;

  // Embree's closest-hit query and nothing else (no hit recomputed in
  // double, no shading data), to measure the ray core against
  // (measure/ray_throughput.h): one rtcIntersect1 call per ray (width 1)
  // or packets of rtcIntersect4/8/16 (width 4, 8, 16; other widths throw
  // std::invalid_argument). Returns how many rays hit something; `t_hit`,
  // if given, receives each ray's float t (infinity for a miss).
  std::size_t embree_closest_hits(std::span<const float_ray> rays, int width, float* t_hit = nullptr) const;

  // Whether this CPU runs Embree's packets of `width` (4, 8, 16) natively
  // rather than as narrower ones.
  static bool native_packet(int width);

  // Whether anything lies strictly between two points.
  bool occluded(const vec3& from, const vec3& to) const;

  // How far a ray leaving a surface starts off it, along the normal (out
  // for reflection, in for refraction): Embree sees origins as floats (7
  // digits), so the lift must be far above float round-off at the scene's
  // scale; a bare epsilon on t fails for grazing rays, whose distance to
  // the surface grows only with t times the grazing angle. 1e-5 of the
  // bounding box diagonal, as for the form factors' shadow rays.
  double surface_offset() const { return offset_; }

  // Area lights for next-event estimation: every emitting triangle (of
  // polygon meshes and tessellated patches) and emitting sphere. Emitting
  // quadrics are not sampled; their light arrives only when a ray hits them.
  double emitter_area() const;
  bool is_sampled_emitter(int surface) const;
  // (u1, u2) in [0, 1)^2 to a point on the emitters, uniform by area; a
  // stratified (u1, u2) gives stratified points.
  emitter_sample sample_emitter(double u1, double u2) const;

 private:
  struct embree_state;
  std::unique_ptr<embree_state> state_;
  double offset_ = 0.0;
};

}  // namespace bounce
