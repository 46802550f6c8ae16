#include "viewer/window.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <glad/gl.h>
// glad first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "image/image.h"

namespace bounce {
namespace {

void on_scroll(GLFWwindow* window, double, double dy) {
  static_cast<window_input*>(glfwGetWindowUserPointer(window))->scroll += dy;
}

// Keys that act however ImGui is focused: Esc (the viewer decides what it
// closes) and Ctrl+Q. ImGui chains its own callback to this one.
void on_key(GLFWwindow* window, int key, int, int action, int mods) {
  if (action != GLFW_PRESS) return;
  auto* input = static_cast<window_input*>(glfwGetWindowUserPointer(window));
  if (key == GLFW_KEY_ESCAPE) ++input->escapes;
  if (key == GLFW_KEY_Q && (mods & GLFW_MOD_CONTROL)) input->quit_now = true;
}

void on_drop(GLFWwindow* window, int count, const char** paths) {
  auto* input = static_cast<window_input*>(glfwGetWindowUserPointer(window));
  for (int i = 0; i < count; ++i) input->dropped.emplace_back(paths[i]);
}

void on_glfw_error(int code, const char* message) {
  std::fprintf(stderr, "glfw error %d: %s\n", code, message);
}

GLFWwindow* try_window(int width, int height, int samples) {
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, samples);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
  GLFWwindow* w = glfwCreateWindow(width, height, "Bounce", nullptr, nullptr);
  if (w) {
    glfwMakeContextCurrent(w);
    if (!gladLoadGL(glfwGetProcAddress)) {
      glfwDestroyWindow(w);
      w = nullptr;
    }
  }
  return w;
}

}  // namespace

GLFWwindow* open_window(int width, int height, int msaa, window_input& input, std::string& error) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    error = "no display for a window (GLFW could not start); use `bounce render` instead";
    return nullptr;
  }
  // Antialiasing: 4x MSAA on a GPU. On Mesa's llvmpipe 4x MSAA doubles the
  // frame time (docs/viewer.md): there the window goes without, so the UI
  // stays fast; --msaa forces either. Headless pictures always use 4x MSAA.
  GLFWwindow* window = try_window(width, height, msaa < 0 ? 4 : msaa);
  if (window && msaa < 0) {
    const char* renderer_name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string name = renderer_name ? renderer_name : "";
    if (name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos) {
      glfwDestroyWindow(window);
      window = try_window(width, height, 0);
      std::printf("bounce: software OpenGL (%s): window antialiasing off to keep frames fast (--msaa 4 forces it)\n",
                  name.c_str());
    }
  }
  if (!window) {
    glfwTerminate();
    error = "cannot open a GL 3.3 core window";
    return nullptr;
  }
  glfwSetWindowUserPointer(window, &input);
  glfwSetScrollCallback(window, on_scroll);  // before ImGui, which chains to them
  glfwSetKeyCallback(window, on_key);
  glfwSetDropCallback(window, on_drop);
  return window;
}

std::string window_title(const std::string& scene_source) {
  std::string name = std::filesystem::path(scene_source).filename().string();
  if (scene_source.starts_with("generated:") || scene_source.starts_with("embedded:") || name.empty())
    name = scene_source;
  return name + " - Bounce";
}

void close_window(GLFWwindow* window) {
  glfwDestroyWindow(window);
  glfwTerminate();
}

bool save_screenshot(const std::string& path, int width, int height, std::string& error) {
  std::vector<unsigned char> rgb(std::size_t(width) * height * 3), flipped(rgb.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  const std::size_t row = std::size_t(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(rgb.data() + std::size_t(height - 1 - y) * row, row, flipped.data() + std::size_t(y) * row);
  return write_png(path, width, height, 3, flipped.data(), error);
}

}  // namespace bounce
