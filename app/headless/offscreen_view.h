// Headless pictures: an OSMesa context with (multisampled) framebuffers, the
// shared mesh renderer drawing into them, and read-back as 8-bit sRGB or
// linear float radiance.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "headless/osmesa_context.h"
#include "image/image.h"
#include "render/mesh_renderer.h"

namespace bounce::headless {

class offscreen_view {
 public:
  // A width x height view with `samples` x MSAA (antialiased edges,
  // emitters' rims included; 0 or 1: none, as the window on software GL).
  // ok() is false, with error(), when GL is unavailable.
  offscreen_view(int width, int height, int samples = 4);
  ~offscreen_view();

  // The mesh is drawn into the left `width` columns only (the rest is for
  // an overlay beside it: the panel); default: the whole width.
  void set_view_width(int width) { view_width_ = width; }

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  // The samples per pixel drawn: those asked for, or the most the GL offers.
  int samples() const { return samples_; }
  gl::mesh_renderer& renderer() { return *renderer_; }

  // Draws and reads back RGBA8, top row first. `overlay`, when given, draws
  // over the view into the same framebuffer (the ImGui panel).
  std::vector<unsigned char> render_rgba8(const glm::mat4& view_projection, const glm::vec3& eye,
                                          const gl::display_settings& settings,
                                          const std::function<void()>& overlay = {});
  // Draws linear radiance (the settings' tone curve is ignored) into float
  // buffers and reads it back unscaled.
  image render_linear(const glm::mat4& view_projection, const glm::vec3& eye, gl::display_settings settings);

 private:
  struct target;
  void draw_into(target& t, const glm::mat4& view_projection, const glm::vec3& eye,
                 const gl::display_settings& settings, const std::function<void()>& overlay);
  osmesa_context context_;
  std::unique_ptr<gl::mesh_renderer> renderer_;
  std::unique_ptr<target> bytes_, floats_;
  int width_, height_, samples_;
  int view_width_ = -1;  // < 0: width_
  std::string error_;
};

}  // namespace bounce::headless
