// Exact answers that solutions are measured against: closed forms of the
// radiosity per vertex for the analytic scenes (furnace, sphere interior,
// emitters over one reflecting polygon), the power they reflect, and the
// relative error of a solution against them.
#pragma once

#include <span>
#include <vector>

#include "measure/curves.h"
#include "mesh/patch_mesh.h"
#include "scene/scene.h"

namespace bounce {

// The closed forms (docs/accuracy-and-closed-forms.md) that a scene's solution is compared with.
enum class exact_kind {
  none,              // no closed form: compare pictures with a path-traced reference
  furnace,           // B = E / (1 - rho) everywhere
  sphere_interior,   // B_j = E_j + rho P_E / ((1 - rho) A)
  emitter_receiver,  // non-reflecting emitters over one reflecting polygon
};

// Per-vertex closed form of the scene (exact_kind != none).
std::vector<rgb> exact_vertex_radiosity(exact_kind kind, const scene& s, const patch_mesh& mesh);
// The total power the scene's surfaces reflect, from the closed form.
rgb exact_reflected_power(exact_kind kind, const scene& s, const patch_mesh& mesh);
// The same from a solution: sum over elements of area x (mean of the
// vertices' B - E), the integral of what the Gouraud view shows.
rgb reflected_power(const patch_mesh& mesh, std::span<const rgb> radiosity);

struct vertex_error {
  double rmse = 0.0;  // RMS difference over vertices and channels / mean of the exact values
  double max = 0.0;   // largest |difference| / exact, exact values below 1e-6 of the largest counted as that
};
// NaN for both when the sizes differ or the exact values are all zero:
// nothing to be relative to.
vertex_error vertex_relative_error(std::span<const rgb> test, std::span<const rgb> exact);

}  // namespace bounce
