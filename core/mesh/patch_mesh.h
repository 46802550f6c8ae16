// The patch mesh: what the radiosity solvers work on and the renderer
// draws. Flat arrays; elements and vertices refer to each other by index.
//
// Radiosity is received and stored at vertices (the Gouraud view needs it
// there); elements are flat triangles, the shooters. A vertex belongs to one
// surface and one material: vertices are shared inside a smooth surface and
// split where the normal breaks (creases) or the material changes.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace bounce {

struct patch_mesh {
  // Vertices
  std::vector<vec3> positions;
  std::vector<vec3> normals;         // unit surface normal (smooth surfaces: the true normal)
  std::vector<vec3> receive_points;  // where form factors are evaluated; see make_patch_mesh
  std::vector<rgb> vertex_rho;       // diffuse reflectance, times the texture's mean
  std::vector<rgb> vertex_emission;  // exitance E = pi * ke
  std::vector<int> vertex_surfaces;
  // Texture coordinates from the tessellation, for the renderer's textures
  // (vertices of textured materials are split where uv jumps); may be
  // empty in meshes built by hand.
  std::vector<vec2> uvs;

  // Elements
  std::vector<glm::ivec3> elements;   // vertex indices, counter-clockwise seen from the front
  std::vector<vec3> element_normals;  // unit geometric normal
  std::vector<double> element_areas;
  std::vector<int> element_surfaces;
  std::vector<int> element_materials;
  std::vector<int> element_patches;  // the patch each element belongs to

  // Per surface: true for the curved ones (spheres, quadrics, patches),
  // whose elements' splits follow the curve (curved_edge_point) rather
  // than the flat facet; false or absent: splits stay in the plane.
  std::vector<bool> curved_surfaces;

  // Patches: the shooters (Cohen 1986 substructuring). Each is a triangle
  // of the coarser bisection level that its elements tile exactly, so it
  // shoots as one polygon while its elements receive separately. With
  // patch_edge == max_edge, patches and elements coincide.
  std::vector<std::array<vec3, 3>> patch_corners;  // counter-clockwise seen from the front
  std::vector<vec3> patch_normals;
  std::vector<double> patch_areas;

  double scene_diagonal = 1.0;        // bounding box diagonal: the scale of every offset
  double max_edge = 0.0;              // the element size it was built for
  std::size_t nonmanifold_faces = 0;  // faces kept with vertices of their own (bad input topology)
  std::size_t uncut_overlaps = 0;     // coplanar overlaps that could not be cut (coplanar_cut.h): they z-fight
  // Ground under solids cut out (coplanar_cut.h): how many loops, their
  // area, and their edges (where the solids stand: contacts).
  std::size_t contact_footprints = 0;
  double contact_area_removed = 0.0;
  std::vector<std::array<vec3, 2>> contact_outline;
  // Shadow outlines cut in (shadow_outlines.h): of how many lights, how
  // many shadows, how many triangles split along them.
  std::size_t shadow_lights = 0;
  std::size_t shadow_outlines = 0;
  std::size_t shadow_triangles_split = 0;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t element_count() const { return elements.size(); }
  std::size_t patch_count() const { return patch_areas.size(); }
};

struct refinement_pass;  // adaptive.h

struct mesher_params {
  double max_edge = 0.0;               // longest element edge; 0 = default_max_edge(scene)
  double crease_angle_degrees = 30.0;  // vertices of faces meeting at a sharper angle are split
  double patch_edge = 0.0;             // longest patch edge; 0 or <= max_edge: patches are the elements
  // > 0: adaptive meshing's a priori pass (adaptive.h), bisecting elements
  // at contacts and near emitters down to this edge
  double a_priori_min_edge = 0.0;
  refinement_pass* a_priori_report = nullptr;  // if set, what the a priori pass did
  // > 0: the smallest edge the solver will split elements down to later
  // (the hierarchical solver); checked here like a_priori_min_edge
  double solver_min_edge = 0.0;
  // the strong lights' shadow outlines are cut into the receivers
  // (shadow_outlines.h)
  bool shadow_outlines = false;
};

// Largest mesh make_patch_mesh builds; past it, a clear error.
inline constexpr std::size_t max_patch_elements = 5'000'000;

// About how many elements make_patch_mesh makes at `max_edge`, before
// anything is allocated: curved surfaces by their tessellation estimate,
// flat triangles by area (bisection leaves triangles of about max_edge^2 / 4
// or more), and at least one element each. A double: absurd requests
// overflow any integer.
double estimate_patch_elements(const scene& s, double max_edge);

// Builds the patch mesh with OpenMesh: every surface tessellated, welded
// into one connected mesh per smooth piece, and flat faces refined by
// longest-edge bisection (Rivara) until no edge exceeds max_edge. An edge
// split divides both triangles beside it, so the mesh stays conforming: no
// T-vertices inside a surface. Curved surfaces are tessellated at max_edge
// directly, so their vertices stay on the true surface.
//
// Coplanar overlaps: where a flat surface lies in the plane of another
// facing the same way (within coplanar_relative_tolerance of the scene's
// diagonal, e.g. a light 0.1 mm under a ceiling), the covered part is cut
// out of the surface behind before meshing (coplanar_cut.h); emitters keep
// all their area.
//
// Receive points: a vertex on the boundary of its surface (e.g. where a wall
// meets the floor) is evaluated a hair inside its own faces (1e-3 of its
// edges' length), the one-sided limit; at the corner itself the neighbour
// is seen exactly edge-on and the form factor would drop to zero.
//
// Returns false with `error` set when the mesh would exceed max_patch_elements.
bool make_patch_mesh(const scene& s, const mesher_params& params, patch_mesh& out, std::string& error);

// Adaptive refinement of a built mesh by conforming longest-edge bisection
// (Rivara's LEPP): each marked element whose longest edge exceeds min_edge
// is bisected once, together with the neighbours that conformity needs, so
// no vertex ends inside another element's edge within a smooth piece of a
// surface (vertices split at creases and material changes bound pieces). Vertices
// keep their indices (new ones are appended: edge midpoints with their
// parent's surface, material and the mean of the two normals; on curved
// surfaces the midpoint of curved_edge_point); elements are
// renumbered and origin[e] names the element of the old mesh that contains
// e. Patches stay (their elements still tile them), except that a patch
// that was a single element follows its element's split. With `times`
// (one per marked element), element marked[i] is bisected times[i] times:
// in rounds, each splitting once every piece still asking. Only the
// surfaces holding a marked element are rebuilt (surfaces share no
// vertices); the other elements come first in the new order, as they were.
// Returns false with `error` past max_patch_elements.
bool refine_patch_mesh(patch_mesh& mesh, std::span<const int> marked, double min_edge, std::vector<int>& origin,
                       std::string& error, std::span<const int> times = {});

// An element's corners, counter-clockwise seen from the front.
inline std::array<vec3, 3> element_corners(const patch_mesh& mesh, std::size_t element) {
  const glm::ivec3 t = mesh.elements[element];
  return {mesh.positions[std::size_t(t[0])], mesh.positions[std::size_t(t[1])], mesh.positions[std::size_t(t[2])]};
}

// The mean of an element's corners.
inline vec3 element_centroid(const patch_mesh& mesh, std::size_t element) {
  const glm::ivec3 t = mesh.elements[element];
  return (mesh.positions[std::size_t(t[0])] + mesh.positions[std::size_t(t[1])] + mesh.positions[std::size_t(t[2])]) /
         3.0;
}

// The length of an element's longest edge.
inline double element_longest_edge(const patch_mesh& mesh, std::size_t element) {
  const std::array<vec3, 3> p = element_corners(mesh, element);
  return std::max({glm::length(p[1] - p[0]), glm::length(p[2] - p[1]), glm::length(p[0] - p[2])});
}

// The mean over an element's corners of a per-vertex value (its integral
// over the element, per unit area, when the value is linear across it).
inline rgb element_mean(const patch_mesh& mesh, const std::vector<rgb>& per_vertex, std::size_t element) {
  const glm::ivec3 t = mesh.elements[element];
  return (per_vertex[std::size_t(t[0])] + per_vertex[std::size_t(t[1])] + per_vertex[std::size_t(t[2])]) / 3.0;
}

// The point at t along the curve through p and q that leaves each end
// along its tangent plane: the cubic of a point-normal (PN) triangle's edge
// (Vlachos et al. 2001), which depends on the edge's ends alone, so the
// two triangles beside an edge agree. On a circle, for an edge of 20
// degrees, its midpoint is 3.4e-4 of the radius inside (the chord's: 1.5e-2).
inline vec3 curved_edge_point(const vec3& p, const vec3& np, const vec3& q, const vec3& nq, double t) {
  const vec3 bp = (2.0 * p + q - glm::dot(q - p, np) * np) / 3.0;
  const vec3 bq = (2.0 * q + p - glm::dot(p - q, nq) * nq) / 3.0;
  const double s = 1.0 - t;
  return s * s * s * p + 3.0 * s * s * t * bp + 3.0 * s * t * t * bq + t * t * t * q;
}

// Stops the program (BOUNCE_CHECK) unless the mesh keeps the mesher's
// contract: every element names three vertices of the mesh and one of its
// patches (and the emission and patch arrays are sized to the mesh).
// The solvers check it once when they are made.
void check_mesh_contract(const patch_mesh& mesh);

// Barycentric coordinates of `point` (projected onto the element's plane).
vec3 barycentric(const patch_mesh& mesh, int element, const vec3& point);

// Total area of the mesh, and per surface.
double total_area(const patch_mesh& mesh);

}  // namespace bounce
