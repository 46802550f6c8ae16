#include "render/reflection_probes.h"

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>

namespace bounce::gl {

reflection_probes::~reflection_probes() {
  release();
}

void reflection_probes::release() {
  if (!cubes_.empty()) glDeleteTextures(GLsizei(cubes_.size()), cubes_.data());
  cubes_.clear();
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  framebuffer_ = depth_ = 0;
  size_ = 0;
}

void reflection_probes::resize(std::size_t count, int size) {
  if (count == cubes_.size() && size == size_) return;
  release();
  if (count == 0) return;
  size_ = size;
  cubes_.assign(count, 0);
  glGenTextures(GLsizei(count), cubes_.data());
  const std::vector<float> black(std::size_t(size) * size * 4, 0.0f);
  for (unsigned int cube : cubes_) {
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
    // RGBA16F: RGB16F need not be renderable in GL 3.3.
    for (int face = 0; face < 6; ++face)
      glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_RGBA16F, size, size, 0, GL_RGBA, GL_FLOAT,
                   black.data());
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
      glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  }
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glGenFramebuffers(1, &framebuffer_);
}

void reflection_probes::render_face(std::size_t index, int face, const glm::vec3& centre, float near, float far,
                                    const std::function<void(const glm::mat4&)>& draw) {
  if (index >= cubes_.size() || face < 0 || face > 5) return;
  GLint previous_framebuffer = 0, viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_framebuffer);
  glGetIntegerv(GL_VIEWPORT, viewport);
  const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
  glDisable(GL_SCISSOR_TEST);

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face),
                         cubes_[index], 0);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  glViewport(0, 0, size_, size_);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // GL's cube faces are images seen from inside with these up vectors
  // (the "down" of each face is the next axis), so lookAt's frames match
  // the texel layout that samplerCube reads.
  static const glm::vec3 forward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, near, far);
  draw(projection * glm::lookAt(centre, centre + forward[face], up[face]));

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previous_framebuffer));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  if (scissor) glEnable(GL_SCISSOR_TEST);
}

}  // namespace bounce::gl
