// What the cuts of flat surfaces share (coplanar overlaps and contacts in
// coplanar_cut.h, shadow outlines in shadow_outlines.h): the flat surfaces'
// triangles grouped into planes, a plane's (surface, material) pieces, an
// integer frame in the plane for Clipper's exact polygon booleans, and the
// replacement of a piece's triangles by a triangulation of a region.
#pragma once

#include <array>
#include <map>
#include <utility>
#include <vector>

#include <clipper.hpp>
#include <glm/geometric.hpp>

#include "mesh/polygon_triangulation.h"
#include "scene/scene.h"
#include "scene/tessellate.h"

namespace bounce {

struct triangle_ref {
  int surface = 0;
  int triangle = 0;
  double offset = 0.0;  // along the group's normal
};

// Triangles of one plane: normal within coplanar_max_angle of `normal`,
// centroids within the tolerance of each other along it (chained).
struct plane_group {
  vec3 normal{0.0};
  std::vector<triangle_ref> triangles;
};

// One (surface, material) piece of a plane.
struct piece {
  int surface = 0;
  int material = 0;
  bool emits = false;
  double offset = 0.0;  // mean over its triangles
  std::vector<int> triangles;
};

// The plane's 2D integer frame: e1 x e2 = normal, so counter-clockwise in
// 2D is counter-clockwise seen from the front.
struct plane_frame {
  vec3 origin{0.0}, e1{0.0}, e2{0.0};
  double unit = 1.0;

  plane_frame(const vec3& normal, const vec3& centre, double extent) : origin(centre) {
    const vec3 a = std::abs(normal.x) < 0.6 ? vec3(1, 0, 0) : vec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(a, normal));
    e2 = glm::cross(normal, e1);
    unit = std::max(extent, 1e-300) / double(1 << 29);  // |coordinates| <= 2^28
  }
  ClipperLib::IntPoint project(const vec3& p) const { return integer(exact(p)); }
  vec2 plane_point(const ClipperLib::IntPoint& p) const { return {double(p.X) * unit, double(p.Y) * unit}; }
  // In the plane's own coordinates, unrounded, and back.
  vec2 exact(const vec3& p) const { return {glm::dot(p - origin, e1), glm::dot(p - origin, e2)}; }
  vec3 point(const vec2& x) const { return origin + x.x * e1 + x.y * e2; }
  ClipperLib::IntPoint integer(const vec2& x) const { return {std::llround(x.x / unit), std::llround(x.y / unit)}; }
};

inline bool emitting(const material& m) {
  return m.ke.r > 0.0 || m.ke.g > 0.0 || m.ke.b > 0.0;
}

vec3 triangle_cross(const triangle_mesh& m, int t);
vec3 centroid(const triangle_mesh& m, int t);

// Groups the flat surfaces' triangles into planes (offsets chained within
// `tolerance`).
std::vector<plane_group> plane_groups(const std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                      double tolerance);

// The triangles' corners in the frame, one counter-clockwise ring each
// (zero-area ones left out).
ClipperLib::Paths piece_paths(const triangle_mesh& m, const std::vector<int>& triangles, const plane_frame& frame);

// A ring's bounding box in the integer frame (left/top the least X/Y).
ClipperLib::IntRect box_of(const ClipperLib::Path& path);

// A region's area in integer units: outer rings less their holes.
double tree_area(const ClipperLib::PolyTree& tree);

// Triangulates `region` (Clipper's rings, holes as children) into
// `added`. False (nothing added) if some ring cannot be triangulated.
bool triangulate_region(const ClipperLib::PolyTree& region, std::vector<std::array<int_point, 3>>& added);

// Replaces piece p's triangles in this plane with `added` (integer corners
// in the plane's frame); the replaced triangles are marked in `removed`.
// The piece's own corners keep their vertices; new points interpolate
// position, normal and uv from the piece's triangle they lie deepest in,
// except those in `exact_points`, which are placed where they are exactly.
// With `origins` (one per added triangle: the piece's triangle it lies in)
// a new point is interpolated from its triangle's origin without a search.
void replace_with(triangle_mesh& m, const piece& p, const std::vector<std::array<int_point, 3>>& added,
                  const plane_frame& frame, const std::map<std::pair<long long, long long>, vec2>& exact_points,
                  std::vector<bool>& removed, const std::vector<int>* origins = nullptr);

// replace_with on a triangulation of `region`. False (nothing changed) if
// the region cannot be triangulated.
bool replace_piece(triangle_mesh& m, const piece& p, const ClipperLib::PolyTree& region, const plane_frame& frame,
                   const std::map<std::pair<long long, long long>, vec2>& exact_points, std::vector<bool>& removed);

// Drops the triangles marked removed (one flag list per surface).
void drop_removed(std::vector<triangle_mesh>& tessellated, const std::vector<std::vector<bool>>& removed);

}  // namespace bounce
