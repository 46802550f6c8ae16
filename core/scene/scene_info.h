// Counts and extents of a scene, as `bounce info` prints them.
#pragma once

#include <cstddef>
#include <string>

#include "scene/framing.h"
#include "scene/scene.h"

namespace bounce {

// Element size the mesher uses when none is asked for: 1/24 of the bounding
// box diagonal (about 40 mm in the Cornell box).
double default_max_edge(const scene& s);

// The hierarchical solver's starting element size when none is asked for:
// 1/10 of the diagonal (96 mm in the Cornell box). Elements are split
// where links need them (down to an eighth of it by default).
double hierarchical_max_edge(const scene& s);

struct scene_summary {
  std::size_t surfaces = 0;
  std::size_t polygon_meshes = 0, spheres = 0, quadrics = 0, bezier_surfaces = 0, bspline_surfaces = 0;
  std::size_t polygons = 0;   // faces of the polygon meshes, as given
  std::size_t patches = 0;    // Bezier patches plus B-spline spans
  std::size_t triangles = 0;  // after tessellation at max_edge
  double max_edge = 0.0;
  std::size_t materials = 0;
  std::size_t textures = 0;
  std::size_t emitting_materials = 0;  // used by some surface
  std::size_t emitting_surfaces = 0;
  std::size_t point_lights = 0;
  std::size_t spot_lights = 0;
  std::size_t suns = 0;
  bool sky = false;
  bounds3 bounds;
};

// Largest number of triangles a tessellation may produce before Bounce
// refuses it as absurd (about 2.4 GB of mesh).
inline constexpr std::size_t max_tessellated_triangles = 20'000'000;

// Summarises the scene, tessellating curved surfaces at max_edge. Returns an
// error message instead when the tessellation would exceed the limit above.
std::string summarize_scene(const scene& s, double max_edge, scene_summary& out);

}  // namespace bounce
