// OSMesa calls live in this file only: libOSMesa exports every gl* symbol
// too, so all GL calls elsewhere go through glad's function pointers.
#include "osmesa_context.h"

#include <algorithm>

#include <glad/gl.h>
// glad/gl.h must come first: it defines the GL types osmesa.h needs.
#include <GL/osmesa.h>

namespace bounce::headless {

struct osmesa_context::state {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  // RGBA8, bottom row first
};

namespace {

GLADapiproc osmesa_proc(const char* name) {
  return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name));
}

}  // namespace

osmesa_context::osmesa_context(int width, int height)
    : state_(std::make_unique<state>()), width_(width), height_(height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    error_ = "OSMesa: image size " + std::to_string(width) + "x" + std::to_string(height) + " out of range";
    return;
  }
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  state_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!state_->context) {
    error_ = "OSMesa: cannot create a GL 3.3 core context";
    return;
  }
  state_->buffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
  if (!make_current()) return;
  if (!gladLoadGL(osmesa_proc)) error_ = "OSMesa: glad could not load OpenGL";
}

osmesa_context::~osmesa_context() {
  if (state_ && state_->context) OSMesaDestroyContext(state_->context);
}

bool osmesa_context::make_current() {
  if (!state_->context) return false;
  if (!OSMesaMakeCurrent(state_->context, state_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    error_ = "OSMesa: cannot make the context current";
    return false;
  }
  return true;
}

std::string osmesa_context::renderer() const {
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + ", OpenGL " + (v ? v : "?");
}

std::vector<unsigned char> osmesa_context::read_rgba8() {
  glFinish();  // OSMesa fills the user buffer only when rendering is finished
  std::vector<unsigned char> top_down(state_->buffer.size());
  const std::size_t row = static_cast<std::size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y)
    std::copy_n(state_->buffer.data() + (height_ - 1 - y) * row, row, top_down.data() + y * row);
  return top_down;
}

}  // namespace bounce::headless
