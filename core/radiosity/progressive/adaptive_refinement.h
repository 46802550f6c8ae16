// Adaptive meshing's a posteriori half (Cohen et al. 1986, Wallace 1989),
// during progressive shooting: elements whose vertex radiosities differ by
// more than a tolerance (relative, with an absolute floor in dark regions)
// and elements on a shadow boundary of a strong shooter (its shadow rays
// reach some of their vertices and not others) are bisected (while longer
// than the minimum edge), the solution carried over exactly
// (refine_progressive), and shooting goes on; again each time the unshot
// power has fallen by `refine_every`, until a pass finds nothing to split
// or every marked element is at the minimum edge. The a priori half is the
// mesher's (mesh/a_priori_refinement.h).
#pragma once

#include <string>
#include <vector>

#include "mesh/a_priori_refinement.h"
#include "mesh/patch_mesh.h"

namespace bounce {

struct progressive_state;

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

// The minimum edge the parameters stand for on this mesh.
double resolved_min_edge(const adaptive_params& params, const patch_mesh& mesh);

// Where the solver stands in its refinement schedule.
struct adaptive_progress {
  double next_fraction = 0.5;  // next pass once every emitter has shot and unshot is at or below this
  int passes = 0;
  bool finished = false;  // a pass found nothing to split (or the mesh limit was hit)
  std::vector<refinement_pass> history;
  std::string error;  // why refinement stopped early, if it did
};

// A posteriori marks on a solution (sorted, unique): vertex radiosities
// that differ beyond the tolerance, and shadow boundaries of the shooters
// in the state's shot log (params.shadow_shooters; ray cast again,
// visibility per vertex).
std::vector<int> gradient_marks(const progressive_state& state, const adaptive_params& params);
std::vector<int> shadow_marks(progressive_state& state, const adaptive_params& params);

// Whether the schedule calls for a pass now.
bool refinement_due(const progressive_state& state);

// One a posteriori pass: marks, refines and carries the solution over.
// Returns true if the mesh changed.
bool refine_pass(progressive_state& state);

}  // namespace bounce
