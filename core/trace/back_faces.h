// What share of the camera's view is the back of one-sided surfaces: a
// floor modelled upside down, the inside of a vase. Those show black (they
// receive nothing on that side), which looks like a bug in the renderer;
// `bounce info` and the window's panel say so when it is most of the view.
#pragma once

#include "scene/scene.h"
#include "trace/ray_scene.h"

namespace bounce {

// The fraction of a grid x grid set of camera rays that hit something and
// hit the back of a one-sided surface; 0 when nothing is hit.
double back_face_fraction(const scene& s, const camera& view, const ray_scene& rays, int grid = 32);

// Above this share of the view, the back faces are warned about.
inline constexpr double back_face_warning_fraction = 0.5;

// "the camera sees mostly back faces (62% of what it hits) ..." or empty.
std::string back_face_warning(double fraction);

}  // namespace bounce
