// OSMesa calls live in this file only: libOSMesa exports every gl* symbol
// too, so all GL calls elsewhere go through glad's function pointers.
//
// libOSMesa is opened on first use rather than linked: it brings in
// llvmpipe's LLVM, whose relocations cost every process about 60 ms at
// start-up (a `bounce --version` took 80 ms, 20 ms without it), and most
// commands never draw.
#include "headless/osmesa_context.h"

#include <algorithm>

#include <dlfcn.h>

#include <glad/gl.h>
// glad/gl.h must come first: it defines the GL types osmesa.h needs.
#include <GL/osmesa.h>

namespace bounce::headless {

struct osmesa_context::state {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  // RGBA8, bottom row first
};

namespace {

// The five entry points this file calls, from the library opened once.
struct osmesa_library {
  decltype(&OSMesaCreateContextAttribs) create_context = nullptr;
  decltype(&OSMesaDestroyContext) destroy_context = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc_address = nullptr;
  std::string error;  // why it could not be opened, if it could not
};

template <typename F>
bool find(void* library, const char* name, F& out) {
  out = reinterpret_cast<F>(dlsym(library, name));
  return out != nullptr;
}

osmesa_library open_osmesa() {
  osmesa_library lib;
  // The runtime package installs only the versioned name (libosmesa6: .so.8).
  void* library = nullptr;
  for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"})
    if ((library = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
  if (!library) {
    const char* why = dlerror();
    lib.error = std::string("OSMesa: cannot load libOSMesa.so.8 (Debian package libosmesa6): ") + (why ? why : "");
    return lib;
  }
  // Never closed: contexts may outlive any one owner, and the process ends soon after.
  if (!find(library, "OSMesaCreateContextAttribs", lib.create_context) ||
      !find(library, "OSMesaDestroyContext", lib.destroy_context) ||
      !find(library, "OSMesaMakeCurrent", lib.make_current) ||
      !find(library, "OSMesaGetProcAddress", lib.get_proc_address))
    lib.error = "OSMesa: libOSMesa lacks an entry point (OSMesa 11.2 or later is needed)";
  return lib;
}

const osmesa_library& osmesa() {
  static const osmesa_library lib = open_osmesa();  // thread-safe, once
  return lib;
}

GLADapiproc osmesa_proc(const char* name) {
  return reinterpret_cast<GLADapiproc>(osmesa().get_proc_address(name));
}

}  // namespace

osmesa_context::osmesa_context(int width, int height)
    : state_(std::make_unique<state>()), width_(width), height_(height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    error_ = "OSMesa: image size " + std::to_string(width) + "x" + std::to_string(height) + " out of range";
    return;
  }
  if (!osmesa().error.empty()) {
    error_ = osmesa().error;
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
  state_->context = osmesa().create_context(attributes, nullptr);
  if (!state_->context) {
    error_ = "OSMesa: cannot create a GL 3.3 core context";
    return;
  }
  state_->buffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
  if (!make_current()) return;
  if (!gladLoadGL(osmesa_proc)) error_ = "OSMesa: glad could not load OpenGL";
}

osmesa_context::~osmesa_context() {
  if (state_ && state_->context) osmesa().destroy_context(state_->context);
}

bool osmesa_context::make_current() {
  if (!state_->context) return false;
  if (!osmesa().make_current(state_->context, state_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_)) {
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
