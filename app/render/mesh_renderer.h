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

// The elements of one textured material: a range of mesh_arrays::indices.
struct textured_run {
  int texture = -1;         // index into the scene's textures
  glm::vec3 emitted{0.0f};  // the material's ke: the part of B the texture leaves alone
  std::size_t first = 0;    // first index
  std::size_t count = 0;    // indices
};

// The mesh as the renderer's buffers take it: interleaved position,
// normal, reflectance, element size and uv per vertex, and the triangles:
// those of untextured materials first, in the mesh's order, then one run
// per textured material. Plain CPU work: the window builds it on the
// solver's thread, so that a large mesh's arrival costs the UI thread only
// the copy into GL.
struct mesh_arrays {
  static constexpr std::size_t floats_per_vertex = 12;
  std::vector<float> vertices;  // floats_per_vertex a vertex
  std::vector<unsigned int> indices;
  std::size_t vertex_count = 0;
  float largest_element = 0.0f;
  std::size_t untextured_count = 0;  // indices drawn without a texture
  std::vector<textured_run> textured;
  // The scene the mesh was made from: its textures and background. Held so
  // that the renderer uploads a scene's textures once, not once per mesh.
  std::shared_ptr<const scene> source;
};
// `source` may be null: then nothing is textured and the background is black.
mesh_arrays make_mesh_arrays(const patch_mesh& mesh, std::shared_ptr<const scene> source);

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

  // Uploads the mesh once: positions, normals, reflectances, uvs, indices;
  // and the scene's textures when the scene is not the one uploaded last.
  void upload(const patch_mesh& mesh, std::shared_ptr<const scene> source) {
    upload(make_mesh_arrays(mesh, std::move(source)));
  }
  void upload(const mesh_arrays& arrays);

  // Updates the per-vertex radiosity and unshot buffers in place
  // (glBufferSubData), converting to float. The snapshot must belong to the
  // uploaded mesh (the caller uploads a refined mesh first); one of another
  // size is ignored.
  void update(const radiosity_snapshot& snapshot) { update(solution_colours(snapshot), glm::vec3(snapshot.ambient)); }
  // The same from solution_colours (2 x vertices), converted elsewhere.
  void update(const std::vector<glm::vec3>& colours, const glm::vec3& ambient);

  // Draws the mesh, then the scene's background or sky where nothing was
  // drawn (the radiance that the ray-traced still shows where rays miss,
  // through the same exposure and tone curve). Textured materials show
  // B x texture(uv) / mean(texture), the still's rule (see gouraud.frag).
  void draw(const glm::mat4& view_projection, const glm::vec3& eye, const display_settings& settings) const;

 private:
  struct gl_texture {
    unsigned int id = 0;  // 0: a checker, drawn procedurally
    texture_kind kind = texture_kind::checker;
    glm::vec3 color0{1.0f}, color1{0.0f};
    float scale = 1.0f;
    glm::vec3 inverse_mean{1.0f};  // 1 / the texture's mean, 0 where the mean is 0
  };
  void upload_textures(const std::shared_ptr<const scene>& source);
  void delete_textures();

  unsigned int program_ = 0, wire_program_ = 0, textured_program_ = 0, background_program_ = 0;
  unsigned int vao_ = 0, empty_vao_ = 0;
  unsigned int static_buffer_ = 0, dynamic_buffer_ = 0, index_buffer_ = 0;
  int index_count_ = 0;
  std::size_t vertex_count_ = 0;
  float largest_element_ = 1.0f;
  glm::vec3 ambient_{0.0f};
  std::size_t untextured_count_ = 0;
  std::vector<textured_run> textured_;
  std::shared_ptr<const scene> textures_source_;  // the scene whose textures are uploaded
  std::vector<gl_texture> textures_;
  glm::vec3 background_{0.0f};  // the scene's background and sky, as the still sees them
  bool sky_ = false;
  glm::vec3 zenith_{0.0f}, horizon_{0.0f}, sky_up_{0.0f, 1.0f, 0.0f};
};

}  // namespace bounce::gl
