// An offscreen OpenGL 3.3+ core context through OSMesa (Mesa llvmpipe): no
// display needed. The renderer draws into it exactly as into the window.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace bounce::headless {

class osmesa_context {
 public:
  // Creates a core-profile context with a width x height RGBA colour
  // buffer, makes it current and loads GL through glad. On failure,
  // ok() is false and error() says why.
  osmesa_context(int width, int height);
  ~osmesa_context();
  osmesa_context(const osmesa_context&) = delete;
  osmesa_context& operator=(const osmesa_context&) = delete;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::string renderer() const;  // GL_RENDERER and GL_VERSION

  // Makes this context current again (after another one was used).
  bool make_current();

  // Finishes rendering and returns the default framebuffer as RGBA8, top
  // row first (OSMesa stores rows bottom-up).
  std::vector<unsigned char> read_rgba8();

 private:
  struct state;
  std::unique_ptr<state> state_;
  int width_ = 0;
  int height_ = 0;
  std::string error_;
};

}  // namespace bounce::headless
