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
#include "radiosity/solution.h"
#include "render/curved_display.h"
#include "render/mesh_arrays.h"
#include "render/reflection_probes.h"

namespace bounce::gl {

enum class tone_curve : int { srgb = 0, filmic = 1, linear = 2 };
enum class false_colour : int { none = 0, remaining = 1, element_size = 2 };

struct display_settings {
  double exposure = 1.0;  // displayed value = radiance x exposure
  tone_curve curve = tone_curve::srgb;
  bool ambient = false;  // add the Cohen 1988 ambient term (display only)
  bool wireframe = false;
  false_colour colours = false_colour::none;
  bool highlight_back_faces = false;
  // > 0: the preview before the first solution. Every surface adds rho
  // times this radiance (W / (m^2 sr)), shaded by a light at the eye, so a
  // scene shows its shapes, and its mirrors what they face, before any
  // light is shot. 0 once the solution has light of its own.
  double headlight = 0.0;
};

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

  // Updates the per-vertex radiosity and remaining buffers in place
  // (glBufferSubData), converting to float. The snapshot must belong to the
  // uploaded mesh (the caller uploads a refined mesh first); one of another
  // size is ignored.
  void update(const radiosity_snapshot& snapshot) { update(solution_colours(snapshot), glm::vec3(snapshot.ambient)); }
  // The same from solution_colours (2 x vertices), converted elsewhere.
  void update(const std::vector<glm::vec3>& colours, const glm::vec3& ambient);

  // Renders up to `max_faces` cube-map faces of the specular surfaces'
  // reflection probes that the last upload or update left stale (each
  // update queues two rounds of every face: the second shows mirrors in
  // mirrors). A probe that has never shown the scene as it is drawn now (a
  // new mesh, or the first lit solution after the headlit preview) has its
  // first round drawn at once whatever the limit: a mirror is never black
  // while the scene around it is lit. `headlight` is the draw's
  // display_settings::headlight. The window spends a few milliseconds a
  // frame; pictures for files call it with no limit before drawing.
  // Returns whether faces are still stale.
  bool refresh_reflections(std::size_t max_faces = std::size_t(-1), double headlight = 0.0);

  // Draws the mesh, then the scene's background or sky where nothing was
  // drawn (the radiance that the ray-traced still shows where rays miss,
  // through the same exposure and tone curve). Textured materials show
  // B x texture(uv) / mean(texture), the still's rule (see gouraud.frag);
  // mirrors and glass add what their reflection probe sees.
  void draw(const glm::mat4& view_projection, const glm::vec3& eye, const display_settings& settings) const {
    draw_scene(view_projection, eye, settings, -1);
  }

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
  // draw() without the surface of probe `hidden` (>= 0: a probe's own view).
  void draw_scene(const glm::mat4& view_projection, const glm::vec3& eye, const display_settings& settings,
                  int hidden) const;

  // gouraud.vert/.frag's variants for one kind of framebuffer.
  struct program_set {
    unsigned int plain = 0, textured = 0, mirror = 0, glass = 0;
  };
  program_set programs_[2];  // [0] single-sample framebuffers, [1] multisampled ones
  unsigned int wire_program_ = 0, background_program_ = 0;
  unsigned int vao_ = 0, empty_vao_ = 0;
  unsigned int static_buffer_ = 0, dynamic_buffer_ = 0, index_buffer_ = 0;
  std::size_t outline_first_ = 0, outline_count_ = 0;
  std::size_t vertex_count_ = 0, solution_vertex_count_ = 0;
  std::vector<vertex_blend> blends_;
  std::vector<glm::vec3> expanded_;  // update()'s colours blended out to the display vertices
  float largest_element_ = 1.0f;
  glm::vec3 ambient_{0.0f};
  std::size_t plain_count_ = 0;
  std::vector<draw_chunk> plain_chunks_;  // of the plain range, culled against the view
  std::vector<material_run> runs_;
  std::vector<specular_surface> probe_surfaces_;
  reflection_probes probes_;
  std::size_t stale_faces_ = 0;   // faces left to render, counted down through the rounds
  std::size_t urgent_faces_ = 0;  // of those, the ones drawn whatever the limit (a first round)
  bool probes_headlit_ = false;   // what the probes show: the headlit preview
  std::size_t next_face_ = 0;     // the face to render next, counting on through the probes' faces
  glm::vec3 bounds_min_{0.0f}, bounds_max_{0.0f};
  std::shared_ptr<const scene> textures_source_;  // the scene whose textures are uploaded
  std::vector<gl_texture> textures_;
  glm::vec3 background_{0.0f};  // the scene's background and sky, as the still sees them
  bool sky_ = false;
  glm::vec3 zenith_{0.0f}, horizon_{0.0f}, sky_up_{0.0f, 1.0f, 0.0f};
};

}  // namespace bounce::gl
