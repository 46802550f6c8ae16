// The GLFW window: a GL 3.3 core context with glad loaded, antialiasing
// chosen for the GL at hand, scroll input, and reading back the frame.
#pragma once

#include <deque>
#include <string>
#include <vector>

struct GLFWwindow;

namespace bounce {

// A key, character, mouse button or wheel event as GLFW reported it.
struct input_event {
  enum class kind { key, character, button, scroll } what = kind::key;
  int code = 0;  // the key (GLFW_KEY_*) or the mouse button
  int scancode = 0, action = 0, mods = 0;
  unsigned int codepoint = 0;  // character
  double dx = 0.0, dy = 0.0;   // scroll
};

struct window_input {
  // Events in the order they came, until deliver_input hands them on.
  std::deque<input_event> queue;
  // What deliver_input found for the view since the last frame.
  double scroll = 0.0;               // wheel steps
  int escapes = 0;                   // Esc presses
  bool quit_now = false;             // Ctrl+Q
  int panel_toggles = 0;             // Tab or F1 presses outside a text field
  std::vector<std::string> dropped;  // paths dropped on the window
};

// Hands the queued events to ImGui (its GLFW backend's callbacks, which the
// window does not let GLFW call directly) and to `input`, in order, a
// frame's worth at a time: a key or button released in the frame that
// delivered its press stays queued for the next frame. ImGui 1.86 reads
// keys as states once a frame and keeps no queue of its own, so a tap
// shorter than a frame (Enter in a text field, Tab) was lost; it is now
// seen pressed for one frame. Call once a frame, after glfwPollEvents and
// before ImGui's new frame, with ImGui's GLFW backend initialised.
void deliver_input(GLFWwindow* window, window_input& input);

// The window's title for a scene: "cornell_box.json - Bounce".
std::string window_title(const std::string& scene_source);

// Opens a width x height window. `msaa` samples, or -1: 4 on a GPU and none
// on software GL (llvmpipe renders on the CPU, where 4x MSAA doubles the
// frame time). Null with `error` when there is no display or no GL 3.3.
// `input` queues the window's input events (deliver_input) and must
// outlive the window.
GLFWwindow* open_window(int width, int height, int msaa, window_input& input, std::string& error);

// Destroys the window and ends GLFW.
void close_window(GLFWwindow* window);

// Reads the back buffer (width x height) and writes it as a PNG, top row first.
bool save_screenshot(const std::string& path, int width, int height, std::string& error);

}  // namespace bounce
