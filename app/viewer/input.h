// Mouse and keyboard in the window: what the panel (ImGui) does not take
// moves the camera (orbit, pan, zoom, fly) or becomes one of the panel's
// actions through its shortcut (shortcuts() in panel.h).
#pragma once

#include "scene/orbit.h"
#include "viewer/panel.h"

struct GLFWwindow;

namespace bounce {

struct window_input;

struct pointer_state {
  double x = 0.0, y = 0.0;  // cursor position at the last frame
};

// Reads this frame's input. `dt` is the frame time in seconds (flying
// speed); `fov_y_degrees` scales panning. Display toggles (wireframe, help)
// change `panel` directly; everything else is returned as actions.
// Esc and Ctrl+Q act even while the panel has the keyboard, except in a
// text field being edited; `still_running` makes Esc ask before quitting.
panel_actions handle_input(GLFWwindow* window, window_input& input, pointer_state& pointer, orbit_state& orbit,
                           double fov_y_degrees, bool solver_running, bool still_running, double dt,
                           panel_state& panel);

}  // namespace bounce
