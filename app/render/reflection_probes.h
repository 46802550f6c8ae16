// Cube maps of the scene for the live view's mirrors and glass: one per
// specular surface, rendered from the surface's centre in linear radiance
// (half float). The approximation and its limits are in docs/viewer.md
// ("Mirrors and glass"). The renderer decides what to draw into them and
// when; this class owns the GL objects and the six cameras.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace bounce::gl {

class reflection_probes {
 public:
  reflection_probes() = default;
  ~reflection_probes();
  reflection_probes(const reflection_probes&) = delete;
  reflection_probes& operator=(const reflection_probes&) = delete;

  // `count` cube maps of size x size texels a face, cleared to black.
  void resize(std::size_t count, int size);
  std::size_t count() const { return cubes_.size(); }

  // Renders face `face` (GL's order: +x, -x, +y, -y, +z, -z) of cube
  // `index`: binds its framebuffer and viewport, clears, and calls `draw`
  // with the face camera's view-projection (90 degrees, near and far as
  // given). The caller's framebuffer and viewport are restored after.
  void render_face(std::size_t index, int face, const glm::vec3& centre, float near, float far,
                   const std::function<void(const glm::mat4& view_projection)>& draw);

  // The cube map texture of `index`, for glBindTexture(GL_TEXTURE_CUBE_MAP).
  unsigned int texture(std::size_t index) const { return cubes_[index]; }

 private:
  void release();
  std::vector<unsigned int> cubes_;
  unsigned int framebuffer_ = 0, depth_ = 0;
  int size_ = 0;
};

}  // namespace bounce::gl
