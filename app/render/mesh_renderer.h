// The GL 3.3 core renderer of the patch mesh: mirrors core data into GL
// buffers and draws into whatever context is current (GLFW window or
// OSMesa). Knows nothing about windows or contexts.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

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

class mesh_renderer {
 public:
  mesh_renderer() = default;
  ~mesh_renderer();
  mesh_renderer(const mesh_renderer&) = delete;
  mesh_renderer& operator=(const mesh_renderer&) = delete;

  // Compiles the embedded shaders; false with file:line messages on failure.
  bool init(std::string& error);

  // Uploads the mesh once: positions, normals, reflectances, indices.
  void upload(const patch_mesh& mesh);

  // Updates the per-vertex radiosity and unshot buffers in place
  // (glBufferSubData), converting to float. The snapshot must belong to the
  // uploaded mesh (the caller uploads a refined mesh first); one of another
  // size is ignored.
  void update(const radiosity_snapshot& snapshot);

  void draw(const glm::mat4& view_projection, const glm::vec3& eye, const display_settings& settings) const;

 private:
  std::vector<glm::vec3> colours_;  // radiosity then unshot per vertex, as uploaded
  unsigned int program_ = 0, wire_program_ = 0;
  unsigned int vao_ = 0;
  unsigned int static_buffer_ = 0, dynamic_buffer_ = 0, index_buffer_ = 0;
  int index_count_ = 0;
  std::size_t vertex_count_ = 0;
  float largest_element_ = 1.0f;
  glm::vec3 ambient_{0.0f};
};

}  // namespace bounce::gl
