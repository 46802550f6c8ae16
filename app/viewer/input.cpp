#include "viewer/input.h"

#include <glad/gl.h>
// glad first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <utility>

#include "scene/camera_math.h"
#include "trace/ray_scene.h"
#include "viewer/window.h"

namespace bounce {

namespace {

// Whether rays from `p` along the six axes all meet a surface: the eye is
// in a room (an interior), not outside looking at objects.
bool enclosed(const ray_scene& scene, const vec3& p) {
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0}) {
      vec3 d(0.0);
      d[axis] = sign;
      if (!scene.intersect(p, d)) return false;
    }
  return true;
}

}  // namespace

void keep_eye_in_front_of_walls(orbit_state& orbit, const ray_scene& scene) {
  const camera c = camera_from_orbit(orbit, camera{});
  const vec3 out = c.eye - c.target;
  const double length = glm::length(out);
  if (!(length > 0.0)) return;
  if (const std::optional<ray_hit> hit = scene.intersect(c.target, out / length, 0.0, length))
    orbit.distance = std::max(0.9 * hit->t, 1e-6 * length);  // a tenth of the way back from the wall
}

panel_actions handle_input(GLFWwindow* window, window_input& input, pointer_state& pointer, orbit_state& orbit,
                           const view_frame& frame, bool solver_running, bool still_running, double dt,
                           panel_state& panel) {
  ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  const double dx = x - pointer.x, dy = y - pointer.y;
  pointer.x = x;
  pointer.y = y;
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
  if (!left) pointer.pivot.reset();
  if (!io.WantCaptureMouse) {
    const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    if (left && !pointer.left_down && frame.scene && frame.width > 0 && frame.height > 0) {
      // A drag begins: it turns about the point under the cursor, if any.
      camera c = camera_from_orbit(orbit, frame.base);
      c.width = frame.width;
      c.height = frame.height;
      if (const std::optional<ray_hit> hit = frame.scene->intersect(c.eye, camera_ray_direction(c, x, y)))
        pointer.pivot = hit->point;
      pointer.in_room = enclosed(*frame.scene, c.eye);
    }
    if (right || (left && shift)) {
      orbit_pan(orbit, dx, dy, frame.height, frame.base.fov_y_degrees);
    } else if (left && (dx != 0.0 || dy != 0.0)) {
      orbit_rotate_about(orbit, pointer.pivot.value_or(orbit.target), dx, dy);
      if (frame.scene && pointer.in_room) keep_eye_in_front_of_walls(orbit, *frame.scene);
    }
    if (input.scroll != 0.0) orbit_zoom(orbit, input.scroll);
  }
  pointer.left_down = left;
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
  // Half the viewing distance a second, but never under a fortieth of the
  // scene a second: close to a wall, flying does not crawl.
  const double speed = std::max(orbit.distance, 0.05 * frame.scene_size) * 0.5 * dt;
  orbit_fly(orbit, (down(GLFW_KEY_W) - down(GLFW_KEY_S)) * speed, (down(GLFW_KEY_D) - down(GLFW_KEY_A)) * speed,
            (down(GLFW_KEY_E) - down(GLFW_KEY_Q)) * speed);
  // The axis views, on the keypad or the number row: 1 front, 3 right, 7
  // top; with Ctrl the opposite side.
  const double front = front_yaw_of(frame.base);
  auto pressed = [](int keypad, int row) {
    return ImGui::IsKeyPressed(keypad, false) || ImGui::IsKeyPressed(row, false);
  };
  if (pressed(GLFW_KEY_KP_1, GLFW_KEY_1))
    orbit_axis_view(orbit, io.KeyCtrl ? axis_view::back : axis_view::front, front);
  if (pressed(GLFW_KEY_KP_3, GLFW_KEY_3))
    orbit_axis_view(orbit, io.KeyCtrl ? axis_view::left : axis_view::right, front);
  if (pressed(GLFW_KEY_KP_7, GLFW_KEY_7))
    orbit_axis_view(orbit, io.KeyCtrl ? axis_view::bottom : axis_view::top, front);
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
