// Turning a scene's surfaces into triangles.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace bounce {

// Triangles with per-vertex normals and texture coordinates. Vertices are
// shared between the triangles of one smooth piece (so shading is
// continuous); triangles[i] is counter-clockwise seen from the normal side.
struct triangle_mesh {
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // unit, one per position
  std::vector<vec2> uvs;      // one per position (zeros where there is none)
  std::vector<glm::ivec3> triangles;
  std::vector<int> materials;  // one per triangle
};

// Triangulates every face of a polygon mesh as given (no refinement: flat
// faces need none to be exact; the patch mesher subdivides them). Faces with
// zero area or fewer than 3 distinct corners are skipped and counted in
// *dropped when it is given. Non-convex planar faces are ear-clipped.
triangle_mesh triangulate(const polygon_mesh& mesh, std::size_t* dropped = nullptr);

// Tessellates a curved surface so that no triangle edge is longer than about
// max_edge (scene units) and, for the analytic shapes, every vertex lies on
// the exact surface. Edges are also short enough that the normal turns by
// at most about curved_degrees_per_edge along one, whatever max_edge says
// (along the grid's lines; a cell's diagonal turns up to sqrt 2 times that):
// a flat facet strays inside the surface between its vertices (at 45
// degrees a facet, 8% of a sphere's radius; at 20, 1.5%), and the teapot at
// the default element size was an octagon.
constexpr double curved_degrees_per_edge = 20.0;
triangle_mesh tessellate(const sphere& s, double max_edge);
triangle_mesh tessellate(const quadric& q, double max_edge);
triangle_mesh tessellate(const bezier_surface& b, double max_edge);
triangle_mesh tessellate(const bspline_surface& b, double max_edge);

// Any surface: dispatches on its shape.
triangle_mesh tessellate(const surface& s, double max_edge, std::size_t* dropped = nullptr);

// Number of triangles tessellate() would make, computed without making them;
// used to refuse absurd requests before allocating.
std::size_t estimate_triangles(const surface& s, double max_edge);

// Evaluation of the parametric surfaces, (u, v) in [0, 1]^2 per patch.
vec3 bezier_point(const std::array<vec3, 16>& control, double u, double v);
vec3 bezier_normal(const std::array<vec3, 16>& control, double u, double v);
// (u, v) in [0, cols-3] x [0, rows-3]: span index plus local parameter.
vec3 bspline_point(const bspline_surface& b, double u, double v);
vec3 bspline_normal(const bspline_surface& b, double u, double v);

// Value and gradient of a quadric's polynomial at p.
double quadric_value(const quadric& q, const vec3& p);
vec3 quadric_gradient(const quadric& q, const vec3& p);

}  // namespace bounce
