// Framing a scene: the box that holds its geometry (its size sets the
// scale of clip planes, ray offsets and the orbit camera) and a camera that
// shows all of it, for scenes that bring none of their own (bare OBJ and
// glTF models, JSON scenes without "camera"). y is up.
#pragma once

#include "scene/scene.h"

namespace bounce {

// Axis-aligned bounds of every surface (curved ones by their control
// points or boxes).
struct bounds3 {
  vec3 min{0.0};
  vec3 max{0.0};
};
bounds3 scene_bounds(const scene& s);

// A camera that frames the scene's bounding box, looking horizontally from
// the side that shows the most front-facing area (y is up).
camera fit_camera(const scene& s);

}  // namespace bounce
