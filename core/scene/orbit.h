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
