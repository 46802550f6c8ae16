// Shadow-ray queries against a triangle set, through Embree 3. Embree's
// types stay inside occlusion.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace bounce {

class occlusion_scene {
 public:
  // Builds the BVH over the triangles (positions are copied as floats).
  occlusion_scene(std::span<const vec3> positions, std::span<const glm::ivec3> triangles);
  ~occlusion_scene();
  occlusion_scene(const occlusion_scene&) = delete;
  occlusion_scene& operator=(const occlusion_scene&) = delete;

  // True when a triangle blocks the segment from `from` to `to` (end points
  // excluded: callers lift them off their surfaces first). Thread-safe.
  bool occluded(const vec3& from, const vec3& to) const;

  // The first triangle the segment from `from` to `to` crosses: its index,
  // where along the segment (0..1) and Embree's barycentrics (the point is
  // (1 - u - v) p0 + u p1 + v p2). triangle < 0 when nothing is crossed.
  // What the specular paths follow (specular_paths.h). Thread-safe.
  struct crossing {
    int triangle = -1;
    double t = 0.0;
    double u = 0.0, v = 0.0;
  };
  crossing first_crossing(const vec3& from, const vec3& to) const;

  // How many of the segments from `from` to each target are unblocked.
  // Cast in packets of 8 (Embree's rtcOccluded8). Thread-safe.
  int count_unblocked(const vec3& from, std::span<const vec3> targets) const;

  // Keeps a copy of the first `capacity` segments that count_unblocked
  // casts, so that a benchmark can replay the very same rays one at a time.
  struct segment {
    vec3 from, to;
  };
  void record_segments(std::size_t capacity);
  std::vector<segment> recorded_segments() const;

 private:
  struct embree_state;
  std::unique_ptr<embree_state> state_;
};

}  // namespace bounce
