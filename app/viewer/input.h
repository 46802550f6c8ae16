// Mouse and keyboard in the window: what the panel (ImGui) does not take
// moves the camera (orbit, pan, zoom, fly, axis views) or becomes one of
// the panel's actions through its shortcut (shortcuts() in panel.h).
#pragma once

#include <optional>

#include "scene/orbit.h"
#include "viewer/panel.h"

struct GLFWwindow;

namespace bounce {

class ray_scene;
struct window_input;

struct pointer_state {
  double x = 0.0, y = 0.0;    // cursor position at the last frame
  bool left_down = false;     // the left button at the last frame
  std::optional<vec3> pivot;  // what the drag under way turns about: the point under the cursor when it began
  bool in_room = false;       // the eye was in a room when the drag began: it stays inside (keep_eye_in_front_of_walls)
};

// What the camera moves in: the scene's camera (fov, and its yaw for the
// axis views), the view's size in window coordinates, the scene's size
// (flying speed) and, once built, the scene for rays (null until then):
// the orbit turns about the point under the cursor and never takes the eye
// through a wall.
struct view_frame {
  camera base;
  int width = 0, height = 0;
  double scene_size = 1.0;  // the bounding box's diagonal
  const ray_scene* scene = nullptr;
};

// Reads this frame's input. `dt` is the frame time in seconds (flying
// speed). Display toggles (wireframe, help, the panel) change `panel`
// directly; everything else is returned as actions. Esc and Ctrl+Q act
// even while the panel has the keyboard, except in a text field being
// edited; `still_running` makes Esc ask before quitting.
panel_actions handle_input(GLFWwindow* window, window_input& input, pointer_state& pointer, orbit_state& orbit,
                           const view_frame& frame, bool solver_running, bool still_running, double dt,
                           panel_state& panel);

// Orbiting in a room (the eye enclosed: rays along the six axes all meet
// a surface): when a surface lies between the target and the eye, the eye
// comes forward along the view to just in front of it (the view direction
// kept), so that an orbit never takes it through a wall. Outside, as
// around the Cornell box or a model, the orbit is free.
void keep_eye_in_front_of_walls(orbit_state& orbit, const ray_scene& scene);

}  // namespace bounce
