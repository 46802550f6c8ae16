// One facade over the radiosity solvers: whichever runs, the command
// line, the window, the bench and the tests make it, step it, restart it
// and read its progress and solution the same way.
//
// Each solver is plain data with free functions of its own
// (progressive/progressive.h, hierarchical/solver.h) and knows nothing of
// this file. The facade holds one of them in a std::variant and
// dispatches with std::visit; it times the steps and maps each solver's
// progress to solver_stats (solution.h), whose words it states per solver.
// A third solver plugs in as a new alternative of the variant and a new
// solver_method, without touching the other two.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <variant>

#include "radiosity/hierarchical/state.h"
#include "radiosity/progressive/progressive.h"
#include "radiosity/solution.h"
#include "radiosity/solver_settings.h"

namespace bounce {

struct radiosity_params {
  solver_method method = solver_method::progressive;
  form_factor_params form_factors;
  adaptive_params adaptive;  // progressive only
  hierarchical_params hierarchical;
  std::optional<camera> view;  // hierarchical: the camera that leads refinement (none: view-independent)
};

// The hierarchical solver with what it has published (hierarchical/publication.h).
struct hierarchical_run;

struct radiosity_solver {
  radiosity_solver();
  ~radiosity_solver();
  radiosity_solver(const radiosity_solver&) = delete;
  radiosity_solver& operator=(const radiosity_solver&) = delete;

  std::variant<std::unique_ptr<progressive_state>, std::unique_ptr<hierarchical_run>> state;
  solver_stats stats;  // as of the last step
  // Which vertices of the solved mesh are inside solids
  // (transfer/buried_vertices.h), found as the mesh grows; their published
  // values come from their neighbours outside.
  std::vector<bool> buried;
};

// Makes the solver `params.method` over `mesh` (which, like `s`, must
// outlive it) at B = E.
std::unique_ptr<radiosity_solver> make_radiosity_solver(const scene& s, const patch_mesh& mesh,
                                                        const radiosity_params& params);

// Back to B = E on the input mesh, keeping what does not depend on the
// solution (the form-factor method and its BVH; the progressive solver
// keeps its refined mesh).
void restart_solver(radiosity_solver& solver);

// One step of the solver; updates solver.stats. Returns false when
// nothing is left to do. A step still running at `deadline` ends early
// where it can (the hierarchical link refinement stops splitting pairs;
// stats.cut_short says so); other work runs to the step's end.
bool step_solver(radiosity_solver& solver,
                 std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

// Leads the solver's refinement by `view` from now on, or by no view
// (the hierarchical solver: view_importance.h), keeping what is refined;
// the progressive solver is view-independent and ignores it.
void set_solver_view(radiosity_solver& solver, const std::optional<camera>& view);

// True when the solver's progress meets `stop`.
bool stop_reached(const radiosity_solver& solver, const stop_criterion& stop);

// Steps until `stop` holds (counted from the solver's start) or nothing is
// left; `on_step` (may be empty) runs after every step. The time limit is
// also the steps' deadline: a link refinement still running then stops.
void run_solver(radiosity_solver& solver, const stop_criterion& stop,
                const std::function<void(const radiosity_solver&)>& on_step = {});

solver_method method_of(const radiosity_solver& solver);

// The mesh being solved: the mesher's, or a refinement of it
// (refined_mesh, null until the solver refines).
const patch_mesh& solved_mesh(const radiosity_solver& solver);
std::shared_ptr<const patch_mesh> refined_mesh(const radiosity_solver& solver);

// The solution now, copied.
std::shared_ptr<const radiosity_snapshot> make_snapshot(const radiosity_solver& solver);

// Whether every emitter's light has left at least once: the direct light
// is everywhere (the bench's first picture).
bool all_emission_out(const radiosity_solver& solver);

// The form factors' context (its occlusion scene serves the ray baseline).
const form_factor_context& form_factors_of(const radiosity_solver& solver);

// Each solver's own state, for what only it has (the progressive power
// balance and refinement history, the hierarchical links); null when the
// solver is the other one.
const progressive_state* progressive_of(const radiosity_solver& solver);
const hierarchical_solver* hierarchical_of(const radiosity_solver& solver);

}  // namespace bounce
