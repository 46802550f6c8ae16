#include "viewer/window.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <glad/gl.h>
// glad first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include "image/image.h"

namespace bounce {
namespace {

window_input& input_of(GLFWwindow* window) {
  return *static_cast<window_input*>(glfwGetWindowUserPointer(window));
}

// The callbacks only queue: deliver_input hands the events on in order.
void on_scroll(GLFWwindow* window, double dx, double dy) {
  input_event e;
  e.what = input_event::kind::scroll;
  e.dx = dx;
  e.dy = dy;
  input_of(window).queue.push_back(e);
}

void on_key(GLFWwindow* window, int key, int scancode, int action, int mods) {
  input_of(window).queue.push_back({input_event::kind::key, key, scancode, action, mods, 0, 0.0, 0.0});
}

void on_char(GLFWwindow* window, unsigned int codepoint) {
  input_event e;
  e.what = input_event::kind::character;
  e.codepoint = codepoint;
  input_of(window).queue.push_back(e);
}

void on_button(GLFWwindow* window, int button, int action, int mods) {
  input_event e;
  e.what = input_event::kind::button;
  e.code = button;
  e.action = action;
  e.mods = mods;
  input_of(window).queue.push_back(e);
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
  // ImGui's backend is initialised without callbacks of its own: these
  // queue, and deliver_input calls the backend's in order.
  glfwSetScrollCallback(window, on_scroll);
  glfwSetKeyCallback(window, on_key);
  glfwSetCharCallback(window, on_char);
  glfwSetMouseButtonCallback(window, on_button);
  glfwSetDropCallback(window, on_drop);
  glfwSetWindowFocusCallback(window, ImGui_ImplGlfw_WindowFocusCallback);
  glfwSetCursorEnterCallback(window, ImGui_ImplGlfw_CursorEnterCallback);
  return window;
}

void deliver_input(GLFWwindow* window, window_input& input) {
  const ImGuiIO& io = ImGui::GetIO();
  std::vector<int> pressed_keys, pressed_buttons;  // pressed in this delivery
  auto pressed = [](const std::vector<int>& v, int code) { return std::find(v.begin(), v.end(), code) != v.end(); };
  while (!input.queue.empty()) {
    const input_event e = input.queue.front();
    if (e.what == input_event::kind::key) {
      if (e.action == GLFW_RELEASE && pressed(pressed_keys, e.code)) break;  // next frame: a tap lasts a frame
      ImGui_ImplGlfw_KeyCallback(window, e.code, e.scancode, e.action, e.mods);
      if (e.action == GLFW_PRESS) {
        pressed_keys.push_back(e.code);
        // Keys that act however ImGui is focused: Esc (the viewer decides
        // what it closes) and Ctrl+Q; Tab and F1 unless a text field has
        // the keyboard.
        if (e.code == GLFW_KEY_ESCAPE) ++input.escapes;
        if (e.code == GLFW_KEY_Q && (e.mods & GLFW_MOD_CONTROL)) input.quit_now = true;
        if ((e.code == GLFW_KEY_TAB || e.code == GLFW_KEY_F1) && !io.WantTextInput) ++input.panel_toggles;
      }
    } else if (e.what == input_event::kind::button) {
      if (e.action == GLFW_RELEASE && pressed(pressed_buttons, e.code)) break;
      ImGui_ImplGlfw_MouseButtonCallback(window, e.code, e.action, e.mods);
      if (e.action == GLFW_PRESS) pressed_buttons.push_back(e.code);
    } else if (e.what == input_event::kind::character) {
      ImGui_ImplGlfw_CharCallback(window, e.codepoint);
    } else {
      ImGui_ImplGlfw_ScrollCallback(window, e.dx, e.dy);
      input.scroll += e.dy;
    }
    input.queue.pop_front();
  }
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
