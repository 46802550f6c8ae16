// One solve pipeline for every caller (the commands, the bench, the
// window's worker): mesh the scene for the settings, make the solver over
// the mesh, then step it to a stopping point (run_solver, solver.h).
#pragma once

#include <memory>
#include <string>

#include "mesh/a_priori_refinement.h"
#include "radiosity/solver.h"

namespace bounce {

struct solve_setup {
  std::shared_ptr<const patch_mesh> mesh;  // the mesher's; the solver may refine beyond it
  std::unique_ptr<radiosity_solver> solver;
  refinement_pass a_priori;   // what adaptive meshing's a priori pass did
  double mesh_seconds = 0.0;  // meshing, a priori refinement included
};

// Meshes `s` as `settings` ask (mesher_params_for) and makes the solver
// over the mesh at B = E. `s` must outlive the setup. Returns false with
// the `error` when the mesh cannot be built (past the element limit, or
// needing more memory than is available: memory_estimate.h); `out` is
// then untouched.
bool start_solve(const scene& s, const solver_settings& settings, solve_setup& out, std::string& error);

// start_solve's two halves, for a caller that must keep its old solver
// until the new mesh is built (the window keeps the previous scene running
// when a new one cannot be meshed): the mesh (false with `error`), and the
// solver over a mesh (radiosity_params_for).
bool mesh_for_solve(const scene& s, const solver_settings& settings, solve_setup& out, std::string& error);
std::unique_ptr<radiosity_solver> make_solver_for(const scene& s, const patch_mesh& mesh,
                                                  const solver_settings& settings);

}  // namespace bounce
