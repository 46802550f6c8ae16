#include "headless/offscreen_view.h"

#include <algorithm>

#include <glad/gl.h>

namespace bounce::headless {

// A multisampled colour + depth framebuffer and its single-sample resolve
// (with 0 samples, a plain framebuffer and a copy).
struct offscreen_view::target {
  GLuint msaa_fbo = 0, msaa_colour = 0, msaa_depth = 0, resolve_fbo = 0, resolve_colour = 0;

  target(int width, int height, GLenum format, int samples) {
    glGenRenderbuffers(1, &msaa_colour);
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_colour);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
    glGenRenderbuffers(1, &msaa_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
    glGenFramebuffers(1, &msaa_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_colour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth);
    glGenRenderbuffers(1, &resolve_colour);
    glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour);
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    glGenFramebuffers(1, &resolve_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_colour);
  }
  ~target() {
    const GLuint fbos[] = {msaa_fbo, resolve_fbo};
    const GLuint rbos[] = {msaa_colour, msaa_depth, resolve_colour};
    glDeleteFramebuffers(2, fbos);
    glDeleteRenderbuffers(3, rbos);
  }
};

offscreen_view::offscreen_view(int width, int height, int samples)
    : context_(width, height), width_(width), height_(height), samples_(samples > 1 ? samples : 0) {
  if (!context_.ok()) {
    error_ = context_.error();
    return;
  }
  renderer_ = std::make_unique<gl::mesh_renderer>();
  if (!renderer_->init(error_)) return;
  // More samples than the GL offers leave the multisampled framebuffer
  // without storage, and the picture black: take the most it offers.
  GLint most = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &most);
  if (samples_ > most) samples_ = most > 1 ? int(most) : 0;
  bytes_ = std::make_unique<target>(width, height, GL_RGBA8, samples_);
  glBindFramebuffer(GL_FRAMEBUFFER, bytes_->msaa_fbo);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) error_ = "OSMesa: framebuffer incomplete";
}

offscreen_view::~offscreen_view() {
  // GL objects go before the context that owns them.
  bytes_.reset();
  floats_.reset();
  renderer_.reset();
}

void offscreen_view::draw_into(target& t, const glm::mat4& view_projection, const glm::vec3& eye,
                               const gl::display_settings& settings, const std::function<void()>& overlay) {
  renderer_->refresh_reflections();  // a picture for a file: the mirrors see the solution it shows
  glBindFramebuffer(GL_FRAMEBUFFER, t.msaa_fbo);
  glViewport(0, 0, width_, height_);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glViewport(0, 0, view_width_ >= 0 ? std::min(view_width_, width_) : width_, height_);
  renderer_->draw(view_projection, eye, settings);
  glViewport(0, 0, width_, height_);
  if (overlay) overlay();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.msaa_fbo);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.resolve_fbo);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.resolve_fbo);
}

std::vector<unsigned char> offscreen_view::render_rgba8(const glm::mat4& view_projection, const glm::vec3& eye,
                                                        const gl::display_settings& settings,
                                                        const std::function<void()>& overlay) {
  draw_into(*bytes_, view_projection, eye, settings, overlay);
  std::vector<unsigned char> bottom_up(std::size_t(width_) * height_ * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  std::vector<unsigned char> top_down(bottom_up.size());
  const std::size_t row = std::size_t(width_) * 4;
  for (int y = 0; y < height_; ++y)
    std::copy_n(bottom_up.data() + std::size_t(height_ - 1 - y) * row, row, top_down.data() + std::size_t(y) * row);
  return top_down;
}

image offscreen_view::render_linear(const glm::mat4& view_projection, const glm::vec3& eye,
                                    gl::display_settings settings) {
  if (!floats_) floats_ = std::make_unique<target>(width_, height_, GL_RGBA32F, samples_);
  settings.curve = gl::tone_curve::linear;
  draw_into(*floats_, view_projection, eye, settings, {});
  std::vector<float> bottom_up(std::size_t(width_) * height_ * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_FLOAT, bottom_up.data());
  image out;
  out.width = width_;
  out.height = height_;
  out.pixels.resize(bottom_up.size());
  const std::size_t row = std::size_t(width_) * 3;
  for (int y = 0; y < height_; ++y)
    std::copy_n(bottom_up.data() + std::size_t(height_ - 1 - y) * row, row, out.pixels.data() + std::size_t(y) * row);
  return out;
}

}  // namespace bounce::headless
