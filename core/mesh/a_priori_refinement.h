// Adaptive meshing's a priori half, on geometry alone (in the mesher):
// elements where one surface touches the inside of another (the foot of a
// block on a floor: contact shadows) and elements large for their distance
// to an emitter in front of them are bisected down to the minimum edge.
// The a posteriori half, which refines where the solution changes, belongs
// to the progressive solver (radiosity/progressive/adaptive_refinement.h).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

// The starting element size of adaptive meshing when none is given: 1.5x
// the uniform default (diagonal / 16; 60 mm in the Cornell box).
double adaptive_start_edge(const scene& s);

// The minimum edge when none is given: an eighth of the element size.
inline double default_min_edge(double max_edge) {
  return max_edge / 8.0;
}

// What a refinement pass (a priori here, or a posteriori while solving)
// marked and did.
struct refinement_pass {
  std::size_t gradient = 0;  // a posteriori: vertex radiosities differ
  std::size_t shadow = 0;    // a posteriori: on a shadow boundary
  std::size_t contact = 0;   // a priori: where surfaces touch
  std::size_t emitter = 0;   // a priori: near an emitter
  std::size_t elements_before = 0, elements_after = 0, new_vertices = 0;
  double unshot_fraction = 0.0;  // a posteriori: the progressive solver's unshot fraction when the pass ran
  double seconds = 0.0;
};

// A priori marks on a mesh: elements to bisect for contacts and emitters.
std::vector<int> contact_marks(const patch_mesh& mesh, double min_edge);
std::vector<int> emitter_marks(const patch_mesh& mesh, double min_edge);

// Bisects contact and emitter elements, pass after pass, until none is
// marked. Returns false with `error` past the element limit.
bool refine_a_priori(patch_mesh& mesh, double min_edge, refinement_pass& report, std::string& error);

}  // namespace bounce
