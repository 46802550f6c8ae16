// The GL 3.3 core renderer of the patch mesh: mirrors core data into GL
// buffers and draws into whatever context is current (GLFW window or
// OSMesa). Knows nothing about windows or contexts.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"
#include "radiosity/radiosity.h"

namespace bounce::gl {

enum class tone_curve : int { srgb = 0, filmic = 1, linear = 2 };
enum class false_colour : int { none = 0, unshot = 1, element_size = 2 };

struct display_settings {
  double exposure = 1.0;  // displayed value = radiance x exposure
  tone_curve curve = tone_curve::srgb;
  bool ambient = false;  // add the Cohen 1988 ambient term (display only)
  bool wireframe = false;
  false_colour colours = false_colour::none;
  bool highlight_back_faces = false;
};

// The mesh as the renderer's buffers take it: interleaved position,
// normal, reflectance and element size per vertex, and the triangles.
// Plain CPU work: the window builds it on the solver's thread, so that a
// large mesh's arrival costs the UI thread only the copy into GL.
struct mesh_arrays {
  std::vector<float> vertices;  // 10 floats a vertex
  std::vector<unsigned int> indices;
  std::size_t vertex_count = 0;
  float largest_element = 0.0f;
};
mesh_arrays make_mesh_arrays(const patch_mesh& mesh);

// A solution as the renderer's dynamic buffer takes it: radiosity, then
// the unshot (false colour) per vertex, in float. CPU work, any thread.
std::vector<glm::vec3> solution_colours(const radiosity_snapshot& snapshot);

class mesh_renderer {
 public:
  mesh_renderer() = default;
  ~mesh_renderer();
  mesh_renderer(const mesh_renderer&) = delete;
  mesh_renderer& operator=(const mesh_renderer&) = delete;

  // Compiles the embedded shaders; false with file:line messages on failure.
  bool init(std::string& error);

  // Uploads the mesh once: positions, normals, reflectances, indices.
  void upload(const patch_mesh& mesh) { upload(make_mesh_arrays(mesh)); }
  void upload(const mesh_arrays& arrays);

  // Updates the per-vertex radiosity and unshot buffers in place
  // (glBufferSubData), converting to float. The snapshot must belong to the
  // uploaded mesh (the caller uploads a refined mesh first); one of another
  // size is ignored.
  void update(const radiosity_snapshot& snapshot) { update(solution_colours(snapshot), glm::vec3(snapshot.ambient)); }
  // The same from solution_colours (2 x vertices), converted elsewhere.
  void update(const std::vector<glm::vec3>& colours, const glm::vec3& ambient);

  void draw(const glm::mat4& view_projection, const glm::vec3& eye, const display_settings& settings) const;

 private:
  unsigned int program_ = 0, wire_program_ = 0;
  unsigned int vao_ = 0;
  unsigned int static_buffer_ = 0, dynamic_buffer_ = 0, index_buffer_ = 0;
  int index_count_ = 0;
  std::size_t vertex_count_ = 0;
  float largest_element_ = 1.0f;
  glm::vec3 ambient_{0.0f};
};

}  // namespace bounce::gl
