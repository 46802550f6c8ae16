// The GLFW window: a GL 3.3 core context with glad loaded, antialiasing
// chosen for the GL at hand, scroll input, and reading back the frame.
#pragma once

#include <string>
#include <vector>

struct GLFWwindow;

namespace bounce {

struct window_input {
  double scroll = 0.0;               // wheel steps since the last frame
  int escapes = 0;                   // Esc presses since the last frame
  bool quit_now = false;             // Ctrl+Q since the last frame
  std::vector<std::string> dropped;  // paths dropped on the window since the last frame
};

// The window's title for a scene: "cornell_box.json - Bounce".
std::string window_title(const std::string& scene_source);

// Opens a width x height window. `msaa` samples, or -1: 4 on a GPU and none
// on software GL (llvmpipe renders on the CPU, where 4x MSAA doubles the
// frame time). Null with `error` when there is no display or no GL 3.3.
// `input` receives the scroll wheel and must outlive the window.
GLFWwindow* open_window(int width, int height, int msaa, window_input& input, std::string& error);

// Destroys the window and ends GLFW.
void close_window(GLFWwindow* window);

// Reads the back buffer (width x height) and writes it as a PNG, top row first.
bool save_screenshot(const std::string& path, int width, int height, std::string& error);

}  // namespace bounce
