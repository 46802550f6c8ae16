// Interactive camera navigation as plain maths (GL-free, unit-tested): orbit
// around a target, pan, zoom, fly, frame the scene. y is up.
#pragma once

#include "scene/framing.h"
#include "scene/scene.h"

namespace bounce {

struct orbit_state {
  vec3 target{0.0};
  double distance = 1.0;
  double yaw = 0.0;    // radians about +y; 0 looks along -z
  double pitch = 0.0;  // radians, positive looks down onto the target
};

// The orbit that reproduces a camera's eye and target.
orbit_state orbit_from_camera(const camera& c);
// The camera of an orbit (fov, size and up taken from `base`).
camera camera_from_orbit(const orbit_state& o, const camera& base);

// Mouse drag by (dx, dy) pixels: 0.3 degrees per pixel; pitch stays within
// +-89 degrees so the view never flips.
void orbit_rotate(orbit_state& o, double dx, double dy);
// The same drag turning the camera about `pivot` (the point under the
// cursor when the drag began) instead of the target: the eye and the
// target turn about it together, so the pivot stays where it is on the
// screen while the view turns (Blender's orbit about the point under the
// cursor). The pitch stays within +-89 degrees.
void orbit_rotate_about(orbit_state& o, const vec3& pivot, double dx, double dy);

// The axis views of the numeric keypad (Blender's 1, 3, 7 and with Ctrl
// their opposites), about the same target and at the same distance.
// `front_yaw` is the yaw that counts as the front (the scene camera's,
// squared to the nearest axis by front_yaw_of).
enum class axis_view { front, back, right, left, top, bottom };
void orbit_axis_view(orbit_state& o, axis_view view, double front_yaw);
// A camera's yaw squared to the nearest multiple of 90 degrees.
double front_yaw_of(const camera& c);

// Moves the target in the view plane so the point under the cursor follows
// it: (dx, dy) pixels in a viewport `height` pixels high.
void orbit_pan(orbit_state& o, double dx, double dy, double height, double fov_y_degrees);
// Wheel steps: each brings the eye 10% closer (negative: farther).
void orbit_zoom(orbit_state& o, double steps);
// Moves eye and target together along the view (forward), right and up.
void orbit_fly(orbit_state& o, double forward, double right, double up);
// Looks at the centre of `b` from the current direction, close enough that
// the bounding sphere fills the vertical field of view.
void orbit_frame(orbit_state& o, const bounds3& b, double fov_y_degrees);

}  // namespace bounce
