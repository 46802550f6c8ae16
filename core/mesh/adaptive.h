// Adaptive meshing: elements fine only where the light changes.
//
// A priori (geometry only, in the mesher): elements where one surface
// touches the inside of another (the foot of a block on a floor: contact
// shadows) and elements large for their distance to an emitter in front of
// them are bisected down to the minimum edge.
//
// A posteriori (in the solver, Cohen et al. 1986, Wallace 1989): during
// progressive shooting, elements whose vertex radiosities differ by more
// than a tolerance (relative, with an absolute floor in dark regions) and
// elements on a shadow boundary of a strong shooter (its shadow rays reach
// some of their vertices and not others) are bisected (while longer than
// the minimum edge), the solution carried
// over exactly (refine_radiosity), and shooting goes on; again each time the
// unshot power has fallen by `refine_every`, until a pass finds nothing to
// split or every marked element is at the minimum edge.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

struct radiosity_state;

struct adaptive_params {
  bool enabled = false;
  double tolerance = 0.5;        // split where vertex radiosities differ by more than this fraction of their mean
  double floor = 0.05;           // ... or of this fraction of the scene's mean exitance, whichever is larger
  double min_edge = 0.0;         // elements whose longest edge is at most this are not split; 0 = max_edge / 8
  double refine_every = 3.0;     // a pass each time the unshot power has fallen this many times
  int max_passes = 12;           // a posteriori passes at most
  double shadow_shooters = 0.1;  // shooters with at least this share of the strongest one's shot power cast
                                 // shadows that count ...
  int max_shadow_shooters = 32;  // ... the strongest this many of them
};

// The starting element size of adaptive meshing when none is given: 1.5x
// the uniform default (diagonal / 16; 60 mm in the Cornell box).
double adaptive_start_edge(const scene& s);

// The minimum edge when none is given: an eighth of the element size.
inline double default_min_edge(double max_edge) {
  return max_edge / 8.0;
}

// The minimum edge the parameters stand for on this mesh.
double resolved_min_edge(const adaptive_params& params, const patch_mesh& mesh);

// What a refinement pass marked and did.
struct refinement_pass {
  std::size_t gradient = 0;  // a posteriori: vertex radiosities differ
  std::size_t shadow = 0;    // a posteriori: on a shadow boundary
  std::size_t contact = 0;   // a priori: where surfaces touch
  std::size_t emitter = 0;   // a priori: near an emitter
  std::size_t elements_before = 0, elements_after = 0, new_vertices = 0;
  double unshot_fraction = 0.0;  // when the pass ran
  double seconds = 0.0;
};

// Where the solver stands in its refinement schedule.
struct adaptive_progress {
  double next_fraction = 0.5;  // next pass once every emitter has shot and unshot is at or below this
  int passes = 0;
  bool finished = false;  // a pass found nothing to split (or the mesh limit was hit)
  std::vector<refinement_pass> history;
  std::string error;  // why refinement stopped early, if it did
};

// A priori marks on a mesh: elements to bisect for contacts and emitters.
std::vector<int> contact_marks(const patch_mesh& mesh, double min_edge);
std::vector<int> emitter_marks(const patch_mesh& mesh, double min_edge);

// Bisects contact and emitter elements, pass after pass, until none is
// marked. Returns false with `error` past the element limit.
bool refine_a_priori(patch_mesh& mesh, double min_edge, refinement_pass& report, std::string& error);

// A posteriori marks on a solution (sorted, unique): vertex radiosities
// that differ beyond the tolerance, and shadow boundaries of the shooters
// in the state's shot log (params.shadow_shooters; ray cast again,
// visibility per vertex).
std::vector<int> gradient_marks(const radiosity_state& state, const adaptive_params& params);
std::vector<int> shadow_marks(radiosity_state& state, const adaptive_params& params);

// Whether the schedule calls for a pass now.
bool refinement_due(const radiosity_state& state);

// One a posteriori pass: marks, refines and carries the solution over.
// Returns true if the mesh changed.
bool refine_pass(radiosity_state& state);

}  // namespace bounce
