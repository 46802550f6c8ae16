// The mesh and its solution as the renderer's GL buffers take them: CPU
// work on any thread, which mesh_renderer uploads. Neither this header nor
// its source includes GL, so that the window's solver thread
// (viewer/solver_worker.h) builds them without depending on the renderer.
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"
#include "radiosity/solution.h"
#include "render/curved_display.h"
#include "scene/scene.h"

namespace bounce::gl {

// The elements of one material that needs more than the plain Gouraud
// program: a texture, or mirror and glass (then one run per surface, the
// surface's reflection probe). A range of mesh_arrays::indices.
struct material_run {
  int texture = -1;                         // index into the scene's textures, or -1
  int emission_texture = -1;                // the same, for the emission's detail (material::emission_texture)
  float alpha = 1.0f, alpha_cutoff = 0.0f;  // a cut-out's (material::alpha_cutoff): 0, opaque
  int probe = -1;                           // index into mesh_arrays::probes, or -1
  glm::vec3 emitted{0.0f};                  // the material's ke: the part of B the texture leaves alone
  std::size_t first = 0;                    // first index
  std::size_t count = 0;                    // indices
};

// A specular surface (kr or kt > 0) as the live view approximates it: the
// scene seen from the surface's centre in a cube map (reflection_probes.h).
struct specular_surface {
  int surface = -1;
  glm::vec3 centre{0.0f};  // of the surface's bounding box
  float radius = 0.0f;     // of the sphere about the centre through its farthest vertex
  bool thin = false;       // a sheet (a pane, a mirror): light goes straight through
  bool solid = false;      // bounds a solid, wound outward (closed_surface.h): back faces culled from outside
  glm::vec3 kr{0.0f}, kt{0.0f};
  float ior = 1.0f;
  bool fresnel = false;
  glm::vec3 specular{0.0f};  // Phong highlight of the point lights
  float shininess = 0.0f;
};

// A piece of the plain elements' range, near together in space, with the
// box round its display vertices: the renderer skips the pieces outside
// the view (a room of a furnished interior sees a small part of it).
struct draw_chunk {
  std::size_t first = 0;  // first index
  std::size_t count = 0;  // indices
  glm::vec3 lo{0.0f}, hi{0.0f};
};

// About this many triangles a chunk: few enough draws (a thousand at a
// million triangles), small enough boxes.
inline constexpr std::size_t chunk_triangles = 1024;

// The index ranges of the chunks whose boxes meet the view frustum of
// `view_projection` (clip = view_projection x world), consecutive ones
// merged: (first index, count) pairs.
std::vector<std::pair<std::size_t, std::size_t>> visible_ranges(const std::vector<draw_chunk>& chunks,
                                                                const glm::mat4& view_projection);

// The mesh as the renderer's buffers take it: interleaved position,
// normal, reflectance, element size and uv per vertex, and the triangles:
// those of plain materials first, in chunks ordered along a Morton curve
// of their elements' centres, then one run per textured or specular
// material. Curved surfaces are drawn finer than the
// solver's elements (curved_display.h): the display vertices past the
// mesh's own take blends of the solution's. Plain CPU work: the window
// builds it on the solver's thread, so that a large mesh's arrival costs
// the UI thread only the copy into GL.
struct mesh_arrays {
  static constexpr std::size_t floats_per_vertex = 12;
  std::vector<float> vertices;  // floats_per_vertex a vertex
  std::vector<unsigned int> indices;
  std::size_t vertex_count = 0;           // display vertices
  std::size_t solution_vertex_count = 0;  // the mesh's vertices, the first of them
  std::vector<vertex_blend> blends;       // the rest, as blends of the first
  float largest_element = 0.0f;
  std::size_t plain_count = 0;           // indices drawn by the plain program
  std::vector<draw_chunk> plain_chunks;  // covering [0, plain_count)
  std::size_t outline_first = 0;         // then the elements' edges, pairs of indices (the wireframe)
  std::vector<material_run> runs;
  std::vector<specular_surface> probes;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};
  // The scene the mesh was made from: its textures and background. Held so
  // that the renderer uploads a scene's textures once, not once per mesh.
  std::shared_ptr<const scene> source;
};
// `source` may be null: then nothing is textured and the background is black.
mesh_arrays make_mesh_arrays(const patch_mesh& mesh, std::shared_ptr<const scene> source);

// A solution as the renderer's dynamic buffer takes it: radiosity, then
// the remaining radiosity (false colour) per vertex, in float. CPU work,
// any thread.
std::vector<glm::vec3> solution_colours(const radiosity_snapshot& snapshot);

}  // namespace bounce::gl
