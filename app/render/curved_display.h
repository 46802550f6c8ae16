// A finer tessellation of curved surfaces for display only. The solver's
// elements are flat triangles, coarse where the light is smooth: a sphere
// of radius 1 at the default element size is an octagon in silhouette.
// Each element whose vertex normals disagree is split into k x k smaller
// triangles on its curved point-normal (PN) triangle (Vlachos et al. 2001),
// which passes through the element's vertices with their normals, so the
// silhouette and the reflections follow the surface while the solution is
// still the elements' (interpolated linearly inside each element).
// Plain CPU work, GL-free.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce::gl {

// A display vertex as a blend of up to three solution vertices.
struct vertex_blend {
  unsigned int a = 0, b = 0, c = 0;
  float wa = 1.0f, wb = 0.0f, wc = 0.0f;
};

struct curved_display {
  // Vertices past the mesh's own: where they are, their normal (unit), and
  // the solution vertices whose values they take.
  std::vector<vec3> positions;
  std::vector<vec3> normals;
  std::vector<vertex_blend> blends;
  // Each element's display triangles (vertex indices, the mesh's vertices
  // first, then the ones above), element e's in
  // triangles[3 * first[e] .. 3 * first[e + 1]).
  std::vector<unsigned int> triangles;
  std::vector<std::size_t> first;
  // The elements' edges, as pairs of display vertices (GL_LINES), along
  // the curved surface: the wireframe shows the solver's elements.
  std::vector<unsigned int> outline;
};

// Splits the elements of curved surfaces: a surface whose elements' vertex
// normals span up to `degrees_per_step` degrees (across any element) keeps
// its elements; one spanning more is split into k x k, k = ceil(span / step)
// up to 8, the same k across a surface so that neighbours share their edge
// points (no cracks). The display holds at most `triangle_budget`
// triangles: past it, k shrinks everywhere.
//
// `source`, when given, puts the points of its spheres on the true sphere.
// A step per 12 degrees of normal turn: a silhouette strays by
// r (1 - cos 6 deg), half a pixel on a sphere 200 pixels across.
constexpr double display_degrees_per_step = 12.0;

curved_display make_curved_display(const patch_mesh& mesh, const scene* source = nullptr,
                                   double degrees_per_step = display_degrees_per_step,
                                   std::size_t triangle_budget = 2'000'000);

}  // namespace bounce::gl
