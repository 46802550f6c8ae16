// Two-sided materials (material::two_sided): a surface whose faces have one
// gets a partner surface, its back: the same faces turned over (winding
// reversed, normals negated), in the same place. Everything downstream
// (mesher, solvers, view, tracers) then sees two one-sided surfaces back to
// back, each receiving, reflecting and emitting on its own side, with its
// own radiosity. Coincident faces that face opposite ways neither see nor
// shade each other, and the coplanar cut leaves them alone (it cuts faces
// facing the same way only).
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace bounce {

// Appends the back of every surface with two-sided faces (sets back_of and
// back_side). Spheres cannot be turned over (their normal points out by
// definition): a two-sided sphere is warned about and stays one-sided.
// Returns the warnings. Idempotent: surfaces that have a back get no other.
std::vector<std::string> add_back_sides(scene& s);

// The same shape with its normal reversed, or false for a sphere.
bool turned_over(const shape& in, shape& out);

}  // namespace bounce
