// The rules every scene obeys, whether loaded from a file or built in
// code: what the solvers, the tracer and the view may take for granted.
#pragma once

#include <string>

#include "scene/scene.h"

namespace bounce {

// Checks a scene built in code or loaded: finite numbers, rho in [0,1),
// non-negative emission, sane camera and sizes. Returns an empty string
// when valid, else the first problem.
std::string validate_scene(const scene& s);

// The camera's own rules (eye off the target, up off the view direction,
// fov, size): an error message ("camera: ...") or an empty string.
std::string check_camera(const camera& c);

// A camera's vertical field of view, in degrees: narrower than this the
// view's float projection divides by zero (a black picture), wider is no
// perspective at all.
inline constexpr double min_fov_degrees = 1e-3;
inline constexpr double max_fov_degrees = 179.0;

// True when some surface emits (ke > 0) or a point light shines. A scene
// without is valid (its picture is black) but worth a warning.
bool has_light_source(const scene& s);

// True when something lights the scene as a lamp does: a sky, a punctual
// light, or an emitting material whose glow is not a texture's (a label or
// a screen glows but does not light a room). A model file without one
// opens under the automatic sky.
bool has_lamp(const scene& s);

}  // namespace bounce
