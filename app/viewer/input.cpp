#include "viewer/input.h"

#include <glad/gl.h>
// glad first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <utility>

#include "viewer/window.h"

namespace bounce {

panel_actions handle_input(GLFWwindow* window, window_input& input, pointer_state& pointer, orbit_state& orbit,
                           double fov_y_degrees, bool solver_running, bool still_running, double dt,
                           panel_state& panel) {
  ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  const double dx = x - pointer.x, dy = y - pointer.y;
  pointer = {x, y};
  int window_width = 0, window_height = 0;
  glfwGetWindowSize(window, &window_width, &window_height);
  const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
  if (!io.WantCaptureMouse) {
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    if (right || (left && shift))
      orbit_pan(orbit, dx, dy, window_height, fov_y_degrees);
    else if (left)
      orbit_rotate(orbit, dx, dy);
    if (input.scroll != 0.0) orbit_zoom(orbit, input.scroll);
  }
  input.scroll = 0.0;

  panel_actions keys;
  const bool editing_text = ImGui::IsAnyItemActive() && io.WantTextInput;
  for (; input.escapes > 0; --input.escapes)
    if (!editing_text) keys.quit |= escape(panel, solver_running || still_running).quit;
  keys.quit |= std::exchange(input.quit_now, false);
  for (; input.panel_toggles > 0; --input.panel_toggles) {
    panel.layout.visible = !panel.layout.visible;
    keys.save_layout = true;
  }
  if (io.WantCaptureKeyboard) return keys;
  auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  const double speed = orbit.distance * 0.5 * dt;  // half the viewing distance per second
  orbit_fly(orbit, (down(GLFW_KEY_W) - down(GLFW_KEY_S)) * speed, (down(GLFW_KEY_D) - down(GLFW_KEY_A)) * speed,
            (down(GLFW_KEY_E) - down(GLFW_KEY_Q)) * speed);
  for (int k = 0; k < int(io.InputQueueCharacters.Size); ++k) {
    switch (io.InputQueueCharacters[k]) {
      case 'f':
      case 'F':
        keys.frame_scene = true;
        break;
      case 'c':
      case 'C':
        keys.reset_camera = true;
        break;
      case ' ':
        (solver_running ? keys.pause : keys.resume) = true;
        break;
      case 'n':
      case 'N':
        keys.step = true;
        break;
      case 'r':
      case 'R':
        keys.restart = true;
        break;
      case 'g':
      case 'G':
        panel.display.wireframe = !panel.display.wireframe;
        break;
      case 'p':
      case 'P':
        keys.screenshot = true;
        break;
      case 't':
      case 'T':
        keys.trace_still = true;
        break;
      case 'h':
      case 'H':
        panel.show_help = !panel.show_help;
        break;
      default:
        break;
    }
  }
  return keys;
}

}  // namespace bounce
